#include "bench/sampling/equal_error.h"

#include <algorithm>
#include <cmath>

namespace vesper::bench {
namespace {

struct Range {
  double lo = INFINITY, hi = -INFINITY;
};

Range error_range(const std::vector<CurvePoint>& curve) {
  Range r;
  for (const CurvePoint& p : curve) {
    r.lo = std::min(r.lo, p.relmse);
    r.hi = std::max(r.hi, p.relmse);
  }
  return r;
}

}  // namespace

double time_at_error(std::vector<CurvePoint> curve, double relmse) {
  std::sort(curve.begin(), curve.end(),
            [](const CurvePoint& a, const CurvePoint& b) { return a.relmse > b.relmse; });
  for (size_t i = 0; i + 1 < curve.size(); ++i) {
    const CurvePoint &hi = curve[i], &lo = curve[i + 1];
    if (relmse > hi.relmse || relmse < lo.relmse) continue;
    if (hi.relmse == lo.relmse) return std::min(hi.seconds, lo.seconds);
    const double f = std::log(hi.relmse / relmse) / std::log(hi.relmse / lo.relmse);
    return std::exp(std::log(hi.seconds) + f * std::log(lo.seconds / hi.seconds));
  }
  return NAN;
}

std::vector<double> common_error_levels(const std::vector<CurvePoint>& a,
                                        const std::vector<CurvePoint>& b, int count) {
  const Range ra = error_range(a), rb = error_range(b);
  const double lo = std::log(std::max(ra.lo, rb.lo)), hi = std::log(std::min(ra.hi, rb.hi));
  std::vector<double> levels;
  if (!(lo < hi)) return levels;
  // Midpoints of `count` equal slices: the levels stay clear of the ends,
  // where a single noisy rung decides the interpolation.
  for (int i = 0; i < count; ++i) levels.push_back(std::exp(hi - (hi - lo) * (i + 0.5) / count));
  return levels;
}

}  // namespace vesper::bench
