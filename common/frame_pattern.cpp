#include "common/frame_pattern.h"

#include <cstdio>

namespace vesper {
namespace fs = std::filesystem;

std::pair<size_t, size_t> find_frame_pattern(const std::string& name) {
  const size_t p = name.find('#');
  if (p == std::string::npos) return {0, 0};
  size_t e = p;
  while (e < name.size() && name[e] == '#') ++e;
  return {p, e - p};
}

bool has_frame_pattern(const fs::path& path) {
  return find_frame_pattern(path.filename().string()).second > 0;
}

fs::path frame_path(const fs::path& pattern, long frame) {
  std::string name = pattern.filename().string();
  const auto [pos, len] = find_frame_pattern(name);
  if (len == 0) return pattern;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%0*ld", int(len), frame);
  name.replace(pos, len, buf);
  return pattern.has_parent_path() ? pattern.parent_path() / name : fs::path(name);
}

}  // namespace vesper
