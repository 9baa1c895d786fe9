#include "regress/holm.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vesper::regress {

std::vector<bool> holm_rejections(std::span<const double> p_values, double alpha) {
  const size_t m = p_values.size();
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), size_t(0));
  // NaN (no test) sorts last and is never rejected.
  auto key = [&](size_t i) { return std::isnan(p_values[i]) ? 2.0 : p_values[i]; };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
  std::vector<bool> rejected(m, false);
  for (size_t k = 0; k < m; ++k) {
    if (!(p_values[order[k]] <= alpha / double(m - k))) break;
    rejected[order[k]] = true;
  }
  return rejected;
}

}  // namespace vesper::regress
