#include "common/scene_reference.h"

#include <algorithm>

namespace vesper {

std::string outside_reference_problem(std::string_view ref) {
  if (ref.find('\0') != std::string_view::npos) return "contains a NUL character";
  if (!ref.empty() && ref.front() == '/')
    return "is an absolute path (a farm task's files must be inside its scene directory)";
  for (size_t begin = 0; begin <= ref.size();) {
    const size_t end = std::min(ref.find('/', begin), ref.size());
    if (ref.substr(begin, end - begin) == "..")
      return "has a '..' segment (a farm task's files must be inside its scene directory)";
    begin = end + 1;
  }
  return {};
}

}  // namespace vesper
