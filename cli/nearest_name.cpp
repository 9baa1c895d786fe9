#include "cli/nearest_name.h"

#include <algorithm>
#include <string_view>

namespace vesper::cli {
namespace {

// Optimal string alignment distance: Levenshtein plus the swap of two
// neighbouring letters as one edit ("--sapmle-end" is one typo away).
size_t typo_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

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
