// An environment map with one hot pixel (1e6 in one texel of a 64x32
// lat-long, 1 elsewhere) over an infinite diffuse plane: finite, and the
// image mean matches the analytic irradiance integral (Z-test with the
// renderer's variance AOV, alpha 0.01, Sidak over the three channels).
#include <gtest/gtest.h>

#include <cmath>

#include "stress_checks.h"

namespace vesper::test {
namespace {

constexpr int kW = 64, kH = 32;
constexpr double kRho = 0.5;

// Irradiance on an upward plane from a lat-long map of texel radiance
// L(row, col): texel rows 0..kH/2-1 cover theta in [row, row+1] * pi/kH above
// the plane; each texel's integral of cos(theta) dw is
// dphi * (sin^2 theta1 - sin^2 theta0) / 2 (nearest lookup: constant per texel).
double plane_irradiance(const EnvironmentImage& img, int c) {
  double e = 0;
  const double dphi = 2 * M_PI / kW;
  for (int row = 0; row < kH / 2; ++row) {
    const double t0 = row * M_PI / kH, t1 = (row + 1) * M_PI / kH;
    const double w = dphi * (std::pow(std::sin(t1), 2) - std::pow(std::sin(t0), 2)) / 2;
    for (int col = 0; col < kW; ++col) e += w * img.pixels[size_t(row * kW + col)][c];
  }
  return e;
}

void expect_hot_pixel_integral(int hot_row, int hot_col, float hot) {
  EnvironmentImage img;
  img.width = kW;
  img.height = kH;
  img.pixels.assign(size_t(kW * kH), Rgb(1.f));
  img.pixels[size_t(hot_row * kW + hot_col)] = Rgb(hot, 0.5f * hot, 0.25f * hot);

  SceneDescription d = empty_scene(24, 24, 16, 2);
  d.camera.from = {0.3, 2, -0.1};
  d.camera.to = {0.3, 0, -0.1};
  d.camera.up = {0, 0, -1};
  d.camera.fov_degrees = 40;
  add_quad(d, {-1e4, 0, 1e4}, {2e4, 0, 0}, {0, 0, -2e4},
           add_material(d, "plane", DiffuseMaterialDesc{Rgb(float(kRho))}));
  EnvironmentLightDesc env;
  env.image = img;
  env.file = "hot-pixel";
  add_light(d, env);

  const std::string what = "hot texel " + std::to_string(hot) + " at row " +
                           std::to_string(hot_row) + " col " + std::to_string(hot_col);
  const RenderResult r = render_with_variance(build_scene(d), 16);
  expect_finite(r, what);
  const double crit = sidak_z_critical(kStressAlpha, 3);
  for (int c = 0; c < 3; ++c) {
    const double expect = kRho / M_PI * plane_irradiance(img, c);
    const ImageMean m = image_mean(r, c);
    EXPECT_LT(std::abs(m.mean - expect), crit * m.se)
        << what << ", channel " << c << ": mean " << m.mean << " vs analytic " << expect << " (se "
        << m.se << ")";
  }
}

TEST(HotEnvironmentPixel, MidLatitudeTexelMatchesTheIntegral) {
  expect_hot_pixel_integral(5, 17, 1e6f);
}
TEST(HotEnvironmentPixel, TexelAtThePoleMatchesTheIntegral) {
  expect_hot_pixel_integral(0, 40, 1e6f);
}
TEST(HotEnvironmentPixel, TexelAtTheHorizonMatchesTheIntegral) {
  expect_hot_pixel_integral(kH / 2 - 1, 3, 1e6f);
}
TEST(HotEnvironmentPixel, TexelBelowTheHorizonAddsNothing) {
  expect_hot_pixel_integral(kH / 2, 3, 1e6f);
}

}  // namespace
}  // namespace vesper::test
