#include "worker/render_progress.h"

#include <algorithm>
#include <cctype>

namespace vesper::worker_detail {

std::optional<double> last_render_progress(std::string_view text) {
  constexpr std::string_view kLabel = "render: ";
  for (size_t at = text.rfind(kLabel); at != std::string_view::npos;
       at = at == 0 ? std::string_view::npos : text.rfind(kLabel, at - 1)) {
    size_t i = at + kLabel.size();
    while (i < text.size() && text[i] == ' ') ++i;
    int value = 0, digits = 0;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) && digits < 4) {
      value = value * 10 + (text[i] - '0');
      ++i, ++digits;
    }
    if (digits > 0 && i < text.size() && text[i] == '%') return std::min(value, 100) / 100.0;
  }
  return std::nullopt;
}

}  // namespace vesper::worker_detail
