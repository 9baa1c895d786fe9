#include "renderer/output/exr_encoding.h"

#include <algorithm>
#include <cctype>

namespace vesper {
namespace {

bool starts_with_nocase(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() &&
         std::equal(s.begin(), s.begin() + prefix.size(), prefix.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         });
}

bool is_id_layer(std::string_view layer, const std::vector<std::string>& id_layer_names) {
  if (starts_with_nocase(layer, "crypto")) return true;
  for (const std::string& name : id_layer_names) {
    if (layer.size() == name.size() + 2 && layer.starts_with(name) &&
        std::isdigit(static_cast<unsigned char>(layer[name.size()])) &&
        std::isdigit(static_cast<unsigned char>(layer[name.size() + 1])))
      return true;
  }
  return false;
}

}  // namespace

bool keeps_float32(std::string_view channel, const std::vector<std::string>& id_layer_names) {
  const size_t dot = channel.rfind('.');
  const std::string_view last = dot == std::string_view::npos ? channel : channel.substr(dot + 1);
  if (last != "R" && last != "G" && last != "B" && last != "A") return true;
  if (dot == std::string_view::npos) return false;
  const std::string_view layer = channel.substr(0, dot);
  for (size_t start = 0; start <= layer.size();) {
    const size_t end = std::min(layer.find('.', start), layer.size());
    if (layer.substr(start, end - start) == "variance") return true;
    start = end + 1;
  }
  return is_id_layer(layer, id_layer_names);
}

}  // namespace vesper
