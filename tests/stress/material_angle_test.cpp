// Roughness 0, 1e-4 and 1 for every glossy material, and grazing view and
// light angles. No twins here: checks are finiteness, light where light is
// visible, the emitter bound (stress_checks.h) and, for a delta sun on a
// diffuse plane, the closed form rho/pi * E * cos(theta) in every pixel.
#include <gtest/gtest.h>

#include <cmath>

#include "stress_checks.h"

namespace vesper::test {
namespace {

constexpr double kSky = 0.5, kLamp = 8.0;

// Three spheres of one material over a diffuse floor, a quad light and a sky.
SceneDescription material_scene(const MaterialDesc& m) {
  SceneDescription d = empty_scene(24, 24, 16, 8);
  d.camera.from = {0, 1.0, 3};
  d.camera.to = {0, 0.35, 0};
  add_quad(d, {-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, add_material(d, "floor", DiffuseMaterialDesc{}));
  const uint32_t id = add_material(d, "m", m);
  // Three calls, not a loop over a list: GCC 12 warns falsely (-Wmaybe-uninitialized) on the loop.
  add_sphere(d, {-0.75, 0.35, 0}, 0.35, id);
  add_sphere(d, {0.0, 0.35, 0}, 0.35, id);
  add_sphere(d, {0.75, 0.35, 0}, 0.35, id);
  add_light(d, QuadLightDesc{{-0.5, 2, -0.5}, {1, 0, 0}, {0, 0, 1}, Rgb(float(kLamp))});
  add_light(d, EnvironmentLightDesc{Rgb(float(kSky)), std::nullopt, "", 1, 0});
  return d;
}

void expect_material_plausible(MaterialDesc m, const std::string& what) {
  const SceneDescription d = material_scene(m);
  const RenderResult r = render_with_variance(build_scene(d), 16);
  expect_finite(r, what);
  expect_lit(r, what);
  expect_below_bound(r, kLamp + kSky, what);  // the lamp may be seen in front of the sky
}

class Roughness : public ::testing::TestWithParam<double> {};

TEST_P(Roughness, ConductorIsFiniteAndBounded) {
  expect_material_plausible(ConductorMaterialDesc{GetParam(), Rgb(0.2f, 0.9f, 1.1f), Rgb(3.9f)},
                            "conductor");
}
TEST_P(Roughness, DielectricIsFiniteAndBounded) {
  expect_material_plausible(DielectricMaterialDesc{1.5, GetParam()}, "dielectric");
}
TEST_P(Roughness, PrincipledDielectricIsFiniteAndBounded) {
  expect_material_plausible(PrincipledMaterialDesc{Rgb(0.6f), 0.0, GetParam()}, "principled");
}
TEST_P(Roughness, PrincipledMetalIsFiniteAndBounded) {
  expect_material_plausible(PrincipledMaterialDesc{Rgb(0.9f), 1.0, GetParam()}, "principled metal");
}

INSTANTIATE_TEST_SUITE_P(Extremes, Roughness, ::testing::Values(0.0, 1e-4, 1.0),
                         [](const auto& info) {
                           return info.param == 0   ? std::string("r0")
                                  : info.param == 1 ? std::string("r1")
                                                    : std::string("r1em4");
                         });

// A diffuse plane y = 0 under a delta sun `elevation` degrees above the
// horizon, seen by a camera `view` degrees above the plane: every pixel fully
// on the plane (alpha 1) is exactly rho/pi * E * sin(elevation), no acne, no
// leak; the rest sees black sky.
void expect_grazing_plane(double elevation, double view) {
  constexpr double rho = 0.7, E = 5.0;
  SceneDescription d = empty_scene(32, 32, 4, 4);
  const double v = view * M_PI / 180;
  d.camera.from = {0, std::sin(v) * 10, std::cos(v) * 10};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 20;
  add_quad(d, {-1e4, 0, 1e4}, {2e4, 0, 0}, {0, 0, -2e4},
           add_material(d, "plane", DiffuseMaterialDesc{Rgb(float(rho))}));
  const double e = elevation * M_PI / 180;
  add_light(d, SunLightDesc{normalize(Vec3d(std::cos(e), std::sin(e), 0.3)), Rgb(float(E)), 0});
  const RenderResult r = render(build_scene(d));
  const std::string what =
      "sun at " + std::to_string(elevation) + " deg, view at " + std::to_string(view) + " deg";
  expect_finite(r, what);
  const Vec3d sun = normalize(Vec3d(std::cos(e), std::sin(e), 0.3));
  const double expect = rho / M_PI * E * sun.y;
  const int alpha = r.image.channel_index("A");
  int on_plane = 0, wrong = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const double a = r.image.at(x, y, alpha), l = pixel_luminance(r.image, x, y);
      if (a == 1.0) {
        ++on_plane;
        // Delta light, no noise: float rounding only.
        if (std::abs(l - expect) > 1e-3 * expect && wrong++ < 3)
          ADD_FAILURE() << what << ": pixel " << x << "," << y << " = " << l << ", expected "
                        << expect;
      } else if (a == 0.0 && l != 0.0 && wrong++ < 3) {
        ADD_FAILURE() << what << ": sky pixel " << x << "," << y << " = " << l;
      }
    }
  EXPECT_GT(on_plane, 32 * 4) << what;
  EXPECT_EQ(wrong, 0) << what;
}

TEST(GrazingAngles, SunAtHalfADegreeOnAPlaneSeenFromAbove) { expect_grazing_plane(0.5, 60); }
TEST(GrazingAngles, SunAt0p01DegreesOnAPlaneSeenFromAbove) { expect_grazing_plane(0.01, 60); }
TEST(GrazingAngles, PlaneSeenAtHalfADegree) { expect_grazing_plane(30, 0.5); }
TEST(GrazingAngles, BothGrazing) { expect_grazing_plane(0.05, 0.05); }

// A quad light standing on the floor (tilted 0.01 degrees), emitting along
// it: its light reaches the floor at grazing angles; the camera looks along
// the floor from 0.01 units above it. Finite, lit and bounded.
TEST(GrazingAngles, QuadLightAlmostParallelToTheViewAndFloor) {
  SceneDescription d = material_scene(PrincipledMaterialDesc{Rgb(0.5f), 0.5, 0.3});
  d.lights.clear();
  const double t = 0.01 * M_PI / 180;
  add_light(d, QuadLightDesc{
                   {-1, 1e-6, -1}, {2, 0, 0}, {0, std::cos(t), std::sin(t)}, Rgb(float(kLamp))});
  d.camera.from = {0, 0.01, 3};
  d.camera.to = {0, 0.009, -1};
  const RenderResult r = render_with_variance(build_scene(d), 16);
  expect_finite(r, "edge-on quad light");
  expect_lit(r, "edge-on quad light");
  expect_below_bound(r, kLamp, "edge-on quad light");
}

}  // namespace
}  // namespace vesper::test
