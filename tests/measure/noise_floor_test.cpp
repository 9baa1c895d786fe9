// The reference's noise floor from its two halves, on synthetic Gaussian
// images with a known variance: Z-tests (alpha = 1e-3 two-sided, |z| < 3.29)
// of the estimate against the analytic value, and of its claim to predict
// the reference's real error against the truth.
#include <gtest/gtest.h>

#include <cmath>

#include "measure/noise_floor.h"
#include "renderer/output/image_metrics.h"
#include "synthetic_images.h"

namespace vesper::measure {
namespace {

constexpr double kZ = 3.29;  // two-sided alpha = 1e-3

// Analytic relMSE of the mean of two halves, each truth * (1 + sigma N(0,1)):
// variance of the mean (sigma t)^2 / 2, over (t^2 + 0.01), averaged.
double analytic_floor(const LayeredImage& truth, double sigma) {
  double sum = 0;
  for (float t : truth.pixels) sum += (sigma * t) * (sigma * t) / 2 / (double(t) * t + 0.01);
  return sum / double(truth.pixels.size());
}

// The floor's per-term values (A - B)^2 / (R^2 + 0.01) / 4, for their standard error.
double standard_error(const LayeredImage& a, const LayeredImage& b) {
  const size_t n = a.pixels.size();
  double s = 0, s2 = 0;
  for (size_t i = 0; i < n; ++i) {
    const double r = 0.5 * (a.pixels[i] + b.pixels[i]), d = a.pixels[i] - b.pixels[i];
    const double term = d * d / (r * r + 0.01) / 4;
    s += term;
    s2 += term * term;
  }
  const double mean = s / double(n);
  return std::sqrt((s2 / double(n) - mean * mean) / double(n));
}

TEST(NoiseFloor, MatchesTheAnalyticErrorOfTheMeanOfTwoHalves) {
  std::mt19937_64 rng(7);
  const LayeredImage truth = synth::truth_image(128, 128);
  const double sigma = 0.02;  // small: R^2 in the denominator is then T^2 to 0.1 %
  const LayeredImage a = synth::noisy(truth, sigma, rng), b = synth::noisy(truth, sigma, rng);
  const double floor = reference_noise_floor(a, b);
  const double z = (floor - analytic_floor(truth, sigma)) / standard_error(a, b);
  EXPECT_LT(std::abs(z), kZ) << "floor " << floor << " analytic " << analytic_floor(truth, sigma);
}

TEST(NoiseFloor, PredictsTheReferencesRealError) {
  std::mt19937_64 rng(11);
  const LayeredImage truth = synth::truth_image(96, 96);
  const LayeredImage a = synth::noisy(truth, 0.03, rng), b = synth::noisy(truth, 0.03, rng);
  const LayeredImage reference = mean_of_halves(a, b);
  const double real = relative_mse(reference, truth), floor = reference_noise_floor(a, b);
  // Both estimate the same quantity from independent parts of the noise
  // (A + B and A - B are independent for Gaussians): the difference is
  // zero-mean with variance SE(floor)^2 + SE(real)^2, and SE(real) ~= SE(floor).
  const double z = (floor - real) / (std::sqrt(2.0) * standard_error(a, b));
  EXPECT_LT(std::abs(z), kZ) << "floor " << floor << " real " << real;
}

TEST(NoiseFloor, IdenticalHalvesHaveNoFloorAndTheMeanIsExact) {
  const LayeredImage t = synth::truth_image(8, 8);
  EXPECT_EQ(reference_noise_floor(t, t), 0.0);
  const LayeredImage m = mean_of_halves(synth::rgb_image(2, 2, 1), synth::rgb_image(2, 2, 3));
  for (float v : m.pixels) EXPECT_EQ(v, 2.0f);
  EXPECT_THROW(mean_of_halves(synth::rgb_image(2, 2), synth::rgb_image(3, 2)),
               std::invalid_argument);
}

}  // namespace
}  // namespace vesper::measure
