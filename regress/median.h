#pragma once
// The median of a few numbers (render times, detectable changes).
#include <algorithm>
#include <vector>

namespace vesper::regress {

// The middle value, or the mean of the two middle values; 0 for none.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace vesper::regress
