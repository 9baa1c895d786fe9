#include "jobs/render_overrides.h"

#include "jobs/render_budget.h"

namespace vesper {

std::string join_aovs(const std::vector<std::string>& aovs) {
  std::string s;
  for (const std::string& a : aovs) s += (s.empty() ? "" : ",") + a;
  return s;
}

std::vector<std::string> split_aovs(const std::string& text) {
  std::vector<std::string> out;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find(',', begin);
    if (end == std::string::npos) end = text.size();
    if (end > begin) out.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

std::string overrides_key(const RenderOverrides& o) {
  std::string key;
  if (!o.aovs.empty()) key += ";aovs=" + join_aovs(o.aovs);
  if (o.layer_variance) key += ";layer_variance=1";
  if (o.seed) key += ";seed=" + std::to_string(*o.seed);
  if (o.scale) key += ";scale=" + exact_text(*o.scale);
  if (o.half) key += ";half=1";
  return key;
}

}  // namespace vesper
