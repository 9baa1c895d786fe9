// time_to_error on analytic curves: a Monte Carlo curve relMSE = c / t is a
// straight line of slope -1 in log-log, so interpolation between any two of
// its points and extrapolation from its last one give t = c / target exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "measure/time_to_error.h"

namespace vesper::measure {
namespace {

std::vector<CurvePoint> power_law(double c, double slope, std::vector<double> times) {
  std::vector<CurvePoint> curve;
  for (double t : times) curve.push_back({t, c * std::pow(t, slope)});
  return curve;
}

TEST(TimeToError, InterpolatesAPowerLawExactly) {
  const auto curve = power_law(0.05, -1, {0.1, 0.2, 0.4, 0.8, 1.6});  // relMSE 0.5 .. 0.03125
  for (double target : {0.4, 0.1, 0.05, 0.033}) {
    const TimeToError t = time_to_error(curve, target);
    EXPECT_EQ(t.estimate, TimeEstimate::Interpolated) << target;
    EXPECT_NEAR(t.seconds, 0.05 / target, 1e-12 * (0.05 / target)) << target;
  }
}

TEST(TimeToError, InterpolatesAnyPowerLawExactly) {  // slope -0.7: still a line in log-log
  const auto curve = power_law(2.0, -0.7, {1, 3, 9, 27});
  const double target = 2.0 * std::pow(5.0, -0.7);
  const TimeToError t = time_to_error(curve, target);
  EXPECT_EQ(t.estimate, TimeEstimate::Interpolated);
  EXPECT_NEAR(t.seconds, 5.0, 1e-12);
}

TEST(TimeToError, ExactHitOfAMeasurementIsItsTime) {
  const auto curve = power_law(0.05, -1, {0.1, 0.2, 0.4});
  EXPECT_NEAR(time_to_error(curve, 0.25).seconds, 0.2, 1e-15);
}

TEST(TimeToError, ExtrapolatesWithSlopeMinusOneAndSaysSo) {
  const auto curve = power_law(0.05, -1, {0.1, 0.2, 0.4});  // last relMSE 0.125
  const TimeToError t = time_to_error(curve, 1e-3);
  EXPECT_EQ(t.estimate, TimeEstimate::Extrapolated);
  EXPECT_NEAR(t.seconds, 50.0, 1e-9);
}

TEST(TimeToError, FirstPointAlreadyBelowIsAnUpperBound) {
  const auto curve = power_law(0.05, -1, {0.1, 0.2});  // 0.5, 0.25
  const TimeToError t = time_to_error(curve, 0.9);
  EXPECT_EQ(t.estimate, TimeEstimate::BelowFirst);
  EXPECT_DOUBLE_EQ(t.seconds, 0.1);
}

TEST(TimeToError, FirstCrossingWinsOnANoisyCurve) {
  // Down through 0.1 between t=1 and t=2, back up, then down again: the first crossing counts.
  const std::vector<CurvePoint> curve = {{1, 0.2}, {2, 0.05}, {4, 0.15}, {8, 0.01}};
  const TimeToError t = time_to_error(curve, 0.1);
  EXPECT_EQ(t.estimate, TimeEstimate::Interpolated);
  EXPECT_NEAR(t.seconds, std::sqrt(2.0), 1e-12);  // halfway down in log relMSE
}

TEST(TimeToError, UnusableCurvesGiveNone) {
  EXPECT_EQ(time_to_error({}, 0.1).estimate, TimeEstimate::None);
  EXPECT_EQ(time_to_error({{1, 0}}, 0.1).estimate, TimeEstimate::None);
  EXPECT_EQ(time_to_error({{0, 0.5}}, 0.1).estimate, TimeEstimate::None);
  EXPECT_EQ(time_to_error({{1, NAN}}, 0.1).estimate, TimeEstimate::None);
  EXPECT_STREQ(time_estimate_name(TimeEstimate::Extrapolated), "extrapolated");
}

}  // namespace
}  // namespace vesper::measure
