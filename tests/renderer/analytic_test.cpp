// Closed-form checks of the estimator: a diffuse plane under a parallel quad
// light (irradiance from Lambert's polygon formula) and a sphere under a delta
// sun (no acne at grazing angles).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "analytic_plane.h"
#include "render_stats.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

// A diffuse plane y = 0 seen from above, lit by `light`; each 4x4 tile's mean
// must match rho/pi * E(x) averaged over its pixels (Sidak-corrected t-test).
template <typename L, typename Irradiance>
void expect_plane_matches(const L& light, const Irradiance& irradiance, double camera_height = 2.0,
                          double fov = 70) {
  constexpr double rho = 0.6;
  SceneDescription d = empty_scene(24, 24, 8, 1);
  d.film.filter = FilterType::Box;
  d.camera.from = {0.1, camera_height, 0.2};
  d.camera.to = {0.1, 0, 0.2};
  d.camera.up = {0, 0, -1};
  d.camera.fov_degrees = fov;
  add_quad(d, {-50, 0, 50}, {100, 0, 0}, {0, 0, -100},
           add_material(d, "plane", DiffuseMaterialDesc{Rgb(float(rho))}));
  add_light(d, light);
  const Scene scene = build_scene(d);
  expect_plane_tiles_match(scene, rho, irradiance, 16, 8);
}

TEST(Analytic, DiffusePlaneUnderQuadLightMatchesFormFactor) {
  // 1x1 light at height 1 facing down (cross(e1, e2) = -y); the camera sits
  // below it so that it never sees the one-sided light itself.
  const Vec3d corner{-0.5, 1, -0.5}, e1{1, 0, 0}, e2{0, 0, 1};
  const std::array<Vec3d, 4> verts{corner, corner + e1, corner + e1 + e2, corner + e2};
  constexpr double L = 4.0;
  expect_plane_matches(
      QuadLightDesc{corner, e1, e2, Rgb(float(L))},
      [&](const Vec3d& p) {
        return polygon_irradiance(p, {0, 1, 0}, verts, L);
      },
      0.9, 80);
}

TEST(Analytic, PlaneUnderPointLightFollowsInverseSquareCosine) {
  const Vec3d p{0.3, 1.2, -0.1};
  const double I = 2.0;
  expect_plane_matches(PointLightDesc{p, Rgb(float(I))}, [&](const Vec3d& x) {
    const Vec3d d = p - x;
    return I * d.y / std::pow(length(d), 3.0);
  });
}

TEST(Analytic, PlaneUnderSphereLightGetsTheSphereIrradiance) {
  // A uniform sphere of radiance I / (pi r^2) wholly above the horizon gives
  // E = pi L sin^2(alpha) cos(theta) = I cos(theta) / d^2 (alpha the
  // sphere's angular radius, theta from the normal to its centre), now with
  // noise: the light is sampled by solid angle.
  const Vec3d p{0.3, 1.2, -0.1};
  const double I = 2.0;
  expect_plane_matches(PointLightDesc{p, Rgb(float(I)), 0.6}, [&](const Vec3d& x) {
    const Vec3d d = p - x;
    return I * d.y / std::pow(length(d), 3.0);
  });
}

TEST(Analytic, PlaneUnderSpotLightFollowsSmoothstepFalloff) {
  const Vec3d p{0.0, 1.0, 0.0}, axis = normalize(Vec3d(0.2, -1, 0.1));
  const double I = 3.0, cone = 35, start = 20;
  expect_plane_matches(SpotLightDesc{p, axis, Rgb(float(I)), cone, start}, [&](const Vec3d& x) {
    const Vec3d d = p - x;
    const double dist = length(d), c = dot(-d / dist, axis);
    const double lo = std::cos(cone * M_PI / 180), hi = std::cos(start * M_PI / 180);
    const double t = std::clamp((c - lo) / (hi - lo), 0.0, 1.0);
    return I * t * t * (3 - 2 * t) * d.y / (dist * dist * dist);
  });
}

TEST(Analytic, PlaneUnderSunDiskGetsIrradianceTimesCosine) {
  // A uniform disk wholly above the horizon gives E_perp * cos(theta_centre) exactly.
  const Vec3d dir = normalize(Vec3d(0.5, 1.0, -0.3));
  const double E = 2.5;
  expect_plane_matches(SunLightDesc{dir, Rgb(float(E)), 20.0},
                       [&](const Vec3d&) { return E * dir.y; });
}

TEST(Analytic, PlaneUnderConstantSkyGetsPiL) {
  // The plane sees the upper hemisphere of a uniform sky: E = pi * L, with MIS
  // between the cosine-sampled BSDF and the uniform environment sampling.
  EnvironmentLightDesc sky;
  sky.radiance = Rgb(0.7f);
  expect_plane_matches(sky, [&](const Vec3d&) { return M_PI * 0.7; });
}

// A sphere under a delta sun, seen from the side so much of it is lit at
// grazing angles: every pixel fully on the sphere must match rho/pi*E*cos.
void expect_no_acne(double scale, Vec3d offset) {
  constexpr double rho = 0.8, E = 3.0;
  SceneDescription d = empty_scene(64, 64, 4, 1);
  d.film.filter = FilterType::Box;
  d.camera.from = offset + Vec3d(0, 0, 4) * scale;
  d.camera.to = offset;
  d.camera.fov_degrees = 32;
  const uint32_t m = add_material(d, "m", DiffuseMaterialDesc{Rgb(float(rho))});
  add_sphere(d, offset, 1.0 * scale, m);
  const Vec3d sun = normalize(Vec3d(1, 0.2, -0.15));  // mostly from the side
  add_light(d, SunLightDesc{sun, Rgb(float(E)), 0.0});
  const Scene scene = build_scene(d);
  const RenderResult r = render(scene);

  int checked = 0, acne = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      // Analytic value at the 4 pixel corners; skip pixels not fully on the sphere or near the
      // terminator.
      double lo = 1e30, hi = -1e30;
      bool inside = true;
      for (int c = 0; c < 4; ++c) {
        const Ray ray =
            scene.camera.generate_ray(float(x + (c & 1)), float(y + (c >> 1)), {0.5f, 0.5f});
        const Vec3d o(ray.origin), dir(ray.dir);
        const Vec3d center = (offset - scene.origin) / scene.unit_scale;
        const double rr = scale / scene.unit_scale;
        const Vec3d oc = o - center;
        const double b = dot(oc, dir), cc = dot(oc, oc) - rr * rr, disc = b * b - cc;
        if (disc <= 0) {
          inside = false;
          break;
        }
        const Vec3d p = o + dir * (-b - std::sqrt(disc));
        const double cosl = dot(normalize(p - center), sun);
        lo = std::min(lo, cosl);
        hi = std::max(hi, cosl);
      }
      if (!inside || lo < 0.02) continue;
      ++checked;
      const double v = pixel_luminance(r.image, x, y);
      const double a_lo = rho / M_PI * E * lo, a_hi = rho / M_PI * E * hi;
      if (v < 0.999 * a_lo || v > 1.001 * a_hi) ++acne;
    }
  EXPECT_GT(checked, 300);
  EXPECT_EQ(acne, 0) << "of " << checked << " pixels";
}

TEST(Analytic, NoShadowAcneAtGrazingSunOnUnitSphere) { expect_no_acne(1.0, {0, 0, 0}); }
TEST(Analytic, NoShadowAcneOnTinySphere) { expect_no_acne(1e-4, {0, 0, 0}); }
TEST(Analytic, NoShadowAcneOnHugeSphereFarAway) { expect_no_acne(1e5, {1e5, -2e5, 1e5}); }

}  // namespace
}  // namespace vesper::test
