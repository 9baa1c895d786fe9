#pragma once
// How long a renderer needs to reach a target relMSE, read off its measured
// curve (render time, relMSE) on log-log axes, where Monte Carlo error falls
// as a straight line of slope -1 (relMSE ~ c / time).
#include <string>
#include <vector>

namespace vesper::measure {

struct CurvePoint {
  double seconds = 0;  // render time (> 0)
  double relmse = 0;   // > 0
};

// How the time was obtained.
enum class TimeEstimate {
  Interpolated,  // between the two measurements that bracket the target
  Extrapolated,  // the curve never reached the target: slope -1 from its last point
  BelowFirst,    // already the first point is below the target: its time, an upper bound
  None,          // no usable point (empty curve, non-positive values)
};
const char* time_estimate_name(TimeEstimate e);  // "interpolated", ..., "none"

struct TimeToError {
  double seconds = 0;
  TimeEstimate estimate = TimeEstimate::None;
};

// `curve` in measurement order (increasing spp). The first crossing wins:
// the first point at or below `target` and its predecessor are joined by a
// straight line in (log time, log relMSE). A curve that never gets there is
// continued from its last point with slope -1 (time * relMSE constant). If the
// first point is already below, its time is returned, marked BelowFirst (the
// true time is less: "< t" in tables), rather than a guess below the data.
TimeToError time_to_error(const std::vector<CurvePoint>& curve, double target);

}  // namespace vesper::measure
