#include "regress/html_text.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>

namespace vesper::regress {

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string trimmed_fixed(double value, int decimals) {
  std::string s = fmt::format("{:.{}f}", value, std::max(0, decimals));
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

std::string format_figure(double value, int digits) {
  if (!std::isfinite(value)) return "n/a";
  if (value == 0) return "0";
  const double magnitude = std::fabs(value);
  if (magnitude >= 1e6 || magnitude < 1e-4) return fmt::format("{:.{}g}", value, digits);
  // Decimals so that `digits` significant digits show, none below 1.
  const int decimals = std::max(0, digits - 1 - int(std::floor(std::log10(magnitude))));
  return trimmed_fixed(value, decimals);
}

std::string format_percent(double relative, bool sign) {
  if (!std::isfinite(relative)) return "n/a";
  const std::string figure = format_figure(relative * 100.0, 2);
  return (sign && relative > 0 ? "+" : "") + figure + " %";
}

std::string format_seconds(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "n/a";
  if (seconds < 60) return format_figure(seconds, 3) + " s";
  const long whole = std::lround(seconds);
  return fmt::format("{} min {:02} s", whole / 60, whole % 60);
}

std::string safe_file_name(std::string_view name) {
  std::string out;
  for (char c : name)
    out +=
        (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') ? c : '_';
  if (out.empty() || out == "." || out == "..") out = "_" + out;
  return out;
}

}  // namespace vesper::regress
