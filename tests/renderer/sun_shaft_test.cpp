// Sun shafts (sun_shaft.h): their distances follow their density
// (chi-square), and turning them on changes noise, not the expected image
// (per-tile t-test), for a sun with and without an angle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <boost/math/special_functions/gamma.hpp>

#include "estimator_agreement.h"
#include "renderer/integrator/sun_shaft.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

// Thin fog (as a room's haze) under a roof with a gap, no floor: the sun's
// shaft through the gap, fog beside it lit only by scattering, a dim sky.
// With `second_fog`, the fog beside it is denser (a ray crosses two
// homogeneous spans, and the strategies' weights are more even).
SceneDescription roof_gap_scene(double sun_angle, bool second_fog = false) {
  SceneDescription d = empty_scene(24, 16, 32, 5);
  d.camera.from = {0, 0.8, 3.6};
  d.camera.to = {0, 0.6, 0};
  d.camera.fov_degrees = 55;
  const uint32_t grey = add_material(d, "grey", DiffuseMaterialDesc{Rgb(0.3f)});
  add_quad(d, {-2, 1.5, 2}, {1.8, 0, 0}, {0, 0, -4}, grey);  // the roof, a gap at x in [-0.2, 0.2]
  add_quad(d, {0.2, 1.5, 2}, {1.8, 0, 0}, {0, 0, -4}, grey);
  add_light(d, SunLightDesc{normalize(Vec3d(-0.3, 1, 0.2)), Rgb(3.f, 2.8f, 2.5f), sun_angle});
  add_light(d, EnvironmentLightDesc{Rgb(0.05f), std::nullopt, "", 1, 0});
  add_medium(d, "fog", fog_box(Rgb(0.005f), Rgb(0.06f), 0.5, {-2, 0, -2}, {0, 1.5, 2}));
  add_medium(d, "fog2",
             fog_box(Rgb(0.005f), Rgb(second_fog ? 0.5f : 0.06f), 0.5, {0, 0, -2}, {2, 1.5, 2}));
  return d;
}

RenderOptions with_shafts(bool on) {
  RenderOptions o;
  o.sun_shafts = on;
  return o;
}

// Pearson chi-square p-value of n distances in equal-width bins over the
// spans, against the density integrated numerically (Simpson, 64 steps a bin).
double distance_chi2_p(const Scene& scene, const Ray& ray, int bins, int n) {
  std::vector<MajorantSpan> spans;
  scene.media.majorant_spans(ray, std::numeric_limits<float>::infinity(), spans);
  EXPECT_FALSE(spans.empty());
  const double depth = shaft_optical_depth(scene.media, spans, ray);
  const double t0 = spans.front().t0, t1 = spans.back().t1;
  std::vector<double> observed(size_t(bins), 0.0);
  Sampler s(11);
  for (int i = 0; i < n; ++i) {
    const auto t = sample_shaft_distance(scene.media, spans, ray, depth, s.next1());
    EXPECT_TRUE(t);
    if (!t) continue;
    observed[size_t(std::clamp(int((*t - t0) / (t1 - t0) * bins), 0, bins - 1))] += 1;
  }
  double chi2 = 0, total = 0;
  for (int b = 0; b < bins; ++b) {
    const double a = t0 + (t1 - t0) * b / bins, h = (t1 - t0) / bins / 64;
    double mass = 0;
    for (int k = 0; k < 64; ++k) {
      auto pdf = [&](double t) {
        return shaft_distance_pdf(scene.media, spans, ray, depth, float(t));
      };
      const double x = a + k * h;
      mass += h / 6 * (pdf(x) + 4 * pdf(x + h / 2) + pdf(x + h));
    }
    total += mass;
    chi2 += (observed[size_t(b)] - n * mass) * (observed[size_t(b)] - n * mass) / (n * mass);
  }
  EXPECT_NEAR(total, 1.0, 1e-3);  // the density integrates to 1 over the spans
  return boost::math::gamma_q((bins - 1) / 2.0, chi2 / 2.0);
}

TEST(SunShaft, DistancesFollowTheirDensity) {
  // alpha 0.01 for each of the two rays (one fog; two fogs of different density).
  const SceneDescription d = roof_gap_scene(0.0, true);
  const Scene scene = build_scene(d);
  // Render space = (world - camera position) / unit_scale (scene.h).
  auto ray = [&](Vec3d from, Vec3d dir) {
    const Vec3d o = (from - d.camera.from) / scene.unit_scale;
    return Ray{Vec3(float(o.x), float(o.y), float(o.z)),
               normalize(Vec3(float(dir.x), float(dir.y), float(dir.z))),
               std::numeric_limits<float>::infinity(), 0.f};
  };
  const Ray one_fog = ray({-1.5, 0.7, 3}, {0, 0, -1});
  const Ray two_fogs = ray({-1.9, 0.7, 0.5}, {1, 0, -0.2});
  EXPECT_GT(distance_chi2_p(scene, one_fog, 32, 40000), 0.01);
  EXPECT_GT(distance_chi2_p(scene, two_fogs, 32, 40000), 0.01);
}

TEST(SunShaft, ADeltaSunRendersTheSameExpectedImage) {
  const Scene scene = build_scene(roof_gap_scene(0.0, true));
  const EstimatorNoise noise =
      expect_estimators_agree(scene, with_shafts(true), with_shafts(false));
  // Thin fog: most rays cross it without scattering, so few of them sampled
  // the shaft (median tile standard error ratio measured 0.43). Dropping the
  // shaft's MIS weight fails the t-test above (|t| 7.9 against 4.9).
  EXPECT_LT(noise.median_ratio, 0.6);
}

TEST(SunShaft, ASunWithAnAngleRendersTheSameExpectedImage) {
  // Three strategies share the path: the shaft, next-event estimation at a
  // tracked distance and a phase ray that escapes toward the sun's disk.
  const Scene scene = build_scene(roof_gap_scene(3.0, true));
  const EstimatorNoise noise =
      expect_estimators_agree(scene, with_shafts(true), with_shafts(false));
  EXPECT_LT(noise.median_ratio, 0.6);  // measured 0.48; |t| 7.8 without the shaft's weight
}

TEST(SunShaft, PhaseRaysThatReachAWideSunShareItsPaths) {
  // Looking into a wide, low sun through forward-scattering haze: phase
  // rays from the fog often reach its disk and carry much of the image
  // (add_light_reached's weight); without the shaft's density in their
  // weight, that part is counted twice.
  SceneDescription d = empty_scene(24, 16, 32, 3);
  d.camera.from = {0, 0.8, 3.6};
  d.camera.to = {0, 0.8, 0};
  d.camera.fov_degrees = 55;
  add_light(d, SunLightDesc{normalize(Vec3d(0, 0.2, -1)), Rgb(2.f), 80.0});
  add_medium(d, "haze", fog_box(Rgb(0.005f), Rgb(0.1f), 0.9, {-2, 0, -2}, {2, 1.5, 2}));
  // The t-test is the assertion: it fails at |t| 20 (critical 4.9) without
  // the shaft's density in that weight. Noise is no aim here (the phase rays
  // already sample this glow well: median ratio 1.15).
  expect_estimators_agree(build_scene(d), with_shafts(true), with_shafts(false));
}

}  // namespace
}  // namespace vesper::test
