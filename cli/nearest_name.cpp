#include "cli/nearest_name.h"

#include <algorithm>
#include <string_view>

#include "common/typo_distance.h"

namespace vesper::cli {
namespace {

std::string_view without_dashes(std::string_view s) {
  return s.substr(std::min(s.find_first_not_of('-'), s.size()));
}

}  // namespace

std::optional<std::string> nearest_name(const std::string& typed,
                                        const std::vector<std::string>& names) {
  const size_t letters = without_dashes(typed).size();
  const size_t limit = std::min(std::max<size_t>(1, letters / 3), letters - (letters > 0));
  std::optional<std::string> best;
  size_t best_distance = limit + 1;
  for (const std::string& name : names) {
    const size_t d = typo_distance(typed, name);
    if (d < best_distance) best_distance = d, best = name;
  }
  if (best) return best;
  // A prefix of exactly one name: "--out" -> "--output".
  if (letters < 2) return std::nullopt;
  for (const std::string& name : names) {
    if (name.size() <= typed.size() || name.compare(0, typed.size(), typed) != 0) continue;
    if (best) return std::nullopt;  // ambiguous
    best = name;
  }
  return best;
}

}  // namespace vesper::cli
