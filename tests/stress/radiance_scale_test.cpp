// Radiance from 1e-6 to 1e8: light transport is linear, so a scene whose
// every emitter is scaled by k renders k times its unscaled twin. With one
// light per scene the light choice, and so every sample's path, does not
// depend on k: the twin is exact up to float rounding (bound below).
#include <gtest/gtest.h>

#include <cmath>
#include <variant>

#include "stress_checks.h"

namespace vesper::test {
namespace {

SceneDescription scaled_lights(SceneDescription d, double k) {
  for (auto& l : d.lights)
    std::visit(
        [&](auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, QuadLightDesc> || std::is_same_v<T, EnvironmentLightDesc>)
            g.radiance *= float(k);
          else if constexpr (std::is_same_v<T, SunLightDesc>)
            g.irradiance *= float(k);
          else
            g.intensity *= float(k);
        },
        l.light);
  return d;
}

SceneDescription cornell() { return small_cornell(24, 24, 8); }

// Spheres of every material on a plane under a constant sky.
SceneDescription sky() {
  SceneDescription d = empty_scene(24, 24, 8, 6);
  d.camera.from = {0, 1.2, 3};
  d.camera.to = {0, 0.3, 0};
  add_quad(d, {-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, add_material(d, "floor", DiffuseMaterialDesc{}));
  add_sphere(d, {-0.7, 0.35, 0}, 0.35, add_material(d, "glass", DielectricMaterialDesc{1.5, 0.1}));
  add_sphere(d, {0.0, 0.35, 0}, 0.35, add_material(d, "gold", ConductorMaterialDesc{}));
  add_sphere(d, {0.7, 0.35, 0}, 0.35,
             add_material(d, "plastic", PrincipledMaterialDesc{Rgb(0.5f), 0.0, 0.4}));
  add_light(d, EnvironmentLightDesc{Rgb(0.9f, 0.8f, 1.0f), std::nullopt, "", 1, 0});
  return d;
}

// A sphere light inside a fog box over a floor (volume NEE and equiangular sampling).
SceneDescription sphere_light_in_fog() {
  SceneDescription d = empty_scene(24, 24, 8, 6);
  d.camera.from = {0, 0.8, 3};
  d.camera.to = {0, 0.4, 0};
  add_quad(d, {-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, add_material(d, "floor", DiffuseMaterialDesc{}));
  add_light(d, PointLightDesc{{0, 0.7, 0}, Rgb(2.f), 0.1});
  HomogeneousMediumDesc fog;
  fog.sigma_a = Rgb(0.1f);
  fog.sigma_s = Rgb(0.8f, 0.6f, 0.4f);
  fog.g = 0.4;
  fog.bounds = BoxDesc{{-1, 0, -1}, {1, 1.5, 1}};
  d.media.push_back({"fog", fog});
  return d;
}

// Each sample value is a product of at most ~4 float operations per path
// vertex (max_depth 6: < 30 roundings of 2^-24 each, < 2e-6 relative), and
// pixel means are sums of non-negative values, which keep a relative bound.
// The scaling itself adds one rounding. So |a - k b| <= 1e-5 * k b; an
// absolute 2^-64 per sample covers the fixed-point sums' truncation.
void expect_scaled_twin(const SceneDescription& d, double k, const char* name) {
  const std::string what = std::string(name) + " radiance x " + std::to_string(k);
  const RenderResult twin = render_with_variance(build_scene(d), 8);
  const SceneDescription scaled = scaled_lights(d, k);
  const RenderResult r = render_with_variance(build_scene(scaled), 8);
  expect_finite(r, what);
  expect_lit(r, what);
  int off = 0;
  for (int y = 0; y < r.image.height; ++y)
    for (int x = 0; x < r.image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double a = r.image.at(x, y, c), b = k * double(twin.image.at(x, y, c));
        if (std::abs(a - b) > 1e-5 * std::abs(b) + (1 + k) * 0x1p-64 && off++ < 3)
          ADD_FAILURE() << what << ": pixel " << x << "," << y << " channel " << c << ": " << a
                        << " vs " << b;
      }
  EXPECT_EQ(off, 0) << what;
}

class RadianceScale : public ::testing::TestWithParam<double> {};

TEST_P(RadianceScale, CornellIsItsTwinScaled) {
  expect_scaled_twin(cornell(), GetParam(), "cornell");
}
TEST_P(RadianceScale, SkyIsItsTwinScaled) { expect_scaled_twin(sky(), GetParam(), "sky"); }
TEST_P(RadianceScale, SphereLightInFogIsItsTwinScaled) {
  expect_scaled_twin(sphere_light_in_fog(), GetParam(), "sphere light in fog");
}

INSTANTIATE_TEST_SUITE_P(Decades, RadianceScale, ::testing::Values(1e-6, 1e-3, 1e3, 1e8),
                         [](const auto& info) {
                           const int e = int(std::lround(std::log10(info.param)));
                           return "x1e" + (e < 0 ? "m" + std::to_string(-e) : std::to_string(e));
                         });

// The radiance bound (stress_checks.h): no pixel brighter than the emitter's
// largest radiance, beyond its noise.
TEST(RadianceBound, CornellAt1e8StaysBelowTheEmitterBound) {
  const double k = 1e8;
  const SceneDescription d = scaled_lights(cornell(), k);
  const RenderResult r = render_with_variance(build_scene(d), 16);
  expect_finite(r, "cornell x 1e8");
  expect_below_bound(r, 17.0 * k, "cornell x 1e8");
}

TEST(RadianceBound, SkyAt1e8StaysBelowTheEmitterBound) {
  const double k = 1e8;
  const SceneDescription d = scaled_lights(sky(), k);
  const RenderResult r = render_with_variance(build_scene(d), 16);
  expect_finite(r, "sky x 1e8");
  expect_below_bound(r, 1.0 * k, "sky x 1e8");
}

}  // namespace
}  // namespace vesper::test
