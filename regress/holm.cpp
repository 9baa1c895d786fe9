#include "regress/holm.h"

#include <algorithm>
#include <numeric>

namespace vesper::regress {

std::vector<bool> holm_rejections(std::span<const double> p_values, double alpha) {
  const size_t m = p_values.size();
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return p_values[a] < p_values[b]; });
  std::vector<bool> rejected(m, false);
  for (size_t k = 0; k < m; ++k) {
    if (!(p_values[order[k]] <= alpha / double(m - k))) break;  // NaN stops too
    rejected[order[k]] = true;
  }
  return rejected;
}

}  // namespace vesper::regress
