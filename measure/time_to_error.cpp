#include "measure/time_to_error.h"

#include <cmath>

namespace vesper::measure {

const char* time_estimate_name(TimeEstimate e) {
  switch (e) {
    case TimeEstimate::Interpolated:
      return "interpolated";
    case TimeEstimate::Extrapolated:
      return "extrapolated";
    case TimeEstimate::BelowFirst:
      return "below_first";
    case TimeEstimate::None:
      break;
  }
  return "none";
}

TimeToError time_to_error(const std::vector<CurvePoint>& curve, double target) {
  if (curve.empty() || !(target > 0)) return {};
  for (const CurvePoint& p : curve)
    if (!(p.seconds > 0) || !(p.relmse > 0) || !std::isfinite(p.seconds) ||
        !std::isfinite(p.relmse))
      return {};
  if (curve.front().relmse <= target) return {curve.front().seconds, TimeEstimate::BelowFirst};
  for (size_t i = 1; i < curve.size(); ++i) {
    if (curve[i].relmse > target) continue;
    const CurvePoint &a = curve[i - 1], &b = curve[i];
    const double le_a = std::log(a.relmse), le_b = std::log(b.relmse);
    // le_a > target >= le_b, so le_a != le_b.
    const double f = (std::log(target) - le_a) / (le_b - le_a);
    const double lt = std::log(a.seconds) + f * (std::log(b.seconds) - std::log(a.seconds));
    return {std::exp(lt), TimeEstimate::Interpolated};
  }
  const CurvePoint& last = curve.back();
  return {last.seconds * last.relmse / target, TimeEstimate::Extrapolated};
}

}  // namespace vesper::measure
