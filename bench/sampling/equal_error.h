#pragma once
// Equal-error time ratios from two time-against-error curves: each curve is a
// ladder of runs (time, relMSE); between neighbouring rungs log(time) is
// interpolated linearly in log(relMSE), the straight line that relMSE ~ 1/t
// gives on a log-log plot.
#include <vector>

namespace vesper::bench {

struct CurvePoint {
  double seconds = 0;
  double relmse = 0;
};

// The time the curve needs for `relmse`, or NaN when relmse lies outside the
// curve's range (no extrapolation). The points need not be sorted.
double time_at_error(std::vector<CurvePoint> curve, double relmse);

// `count` error levels spread evenly (in log) over the inner part of the
// range both curves cover, or none when their ranges do not overlap.
std::vector<double> common_error_levels(const std::vector<CurvePoint>& a,
                                        const std::vector<CurvePoint>& b, int count);

}  // namespace vesper::bench
