// Participating media at density_scale 1e-4 .. 1e5, a camera inside a medium
// and lights inside a dense grid. Where a twin exists it is the same medium
// as a homogeneous box (analytic transmittance, equiangular sampling) against
// a constant-density grid (delta and ratio tracking over the majorant grid):
// two different estimators of one image (per-tile Welch t-test, Sidak, 0.01).
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/volume/majorant_grid.h"
#include "stress_checks.h"
#include "tests/renderer/test_grids.h"
#include "tests/renderer/vdb_fixtures.h"

namespace vesper::test {
namespace {

constexpr double kLightRadiance = 12.0;

// A floor under a quad light (radiance 12), camera outside [-0.7, 0.7]^3.
SceneDescription lit_floor(int max_depth = 8) {
  SceneDescription d = empty_scene(24, 24, 8, max_depth);
  d.camera.from = {0, 0.3, 3.5};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 35;
  add_quad(d, {-3, -1, 3}, {6, 0, 0}, {0, 0, -6}, add_material(d, "floor", DiffuseMaterialDesc{}));
  add_light(d, QuadLightDesc{{-0.5, 1.5, -0.5}, {1, 0, 0}, {0, 0, 1}, Rgb(float(kLightRadiance))});
  return d;
}

const Rgb kSigmaA(0.2f), kSigmaS(1.0f, 0.8f, 0.6f);

HomogeneousMediumDesc homogeneous_box(double density, Vec3d lo, Vec3d hi) {
  HomogeneousMediumDesc m;
  m.sigma_a = kSigmaA * float(density);
  m.sigma_s = kSigmaS * float(density);
  m.g = 0.3;
  m.bounds = BoxDesc{lo, hi};
  return m;
}
// Constant density 1 filling [lo, lo + size]^3 exactly, scaled by `density`.
// The test grid is 0 outside its voxels, so its one-voxel trilinear apron is
// empty space under the majorant: fine voxels (n = 129) keep the null
// collisions there (~ density x voxel size per crossing) cheap at 1e5.
VdbMediumDesc grid_box(double density, Vec3d lo, double size, int n = 129) {
  VdbMediumDesc v;
  v.file = "constant-grid";
  v.density =
      std::make_shared<FunctionGrid>(n, size / (n - 1), lo, [](const Vec3&) { return 1.f; });
  v.density_scale = density;
  v.sigma_a = kSigmaA;
  v.sigma_s = kSigmaS;
  v.g = 0.3;
  return v;
}

// A real VDB file: a 64^3 ball of density 1 - r/R in [-0.7, 0.7]^3.
VdbMediumDesc vdb_ball(const TempDir& dir) {
  const DenseVolume ball = make_volume(
      64, 64, 64,
      [](int i, int j, int k) {
        const double r = std::hypot(i - 31.5, j - 31.5, k - 31.5) / 31.5;
        return float(std::max(0.0, 1.0 - r));
      },
      1.4 / 64, Vec3d(-0.7));
  VdbMediumDesc v;
  v.file = write_volume(dir, "ball.vdb", ball).string();
  v.density = load_vdb_grid(v.file, "density");
  v.sigma_a = kSigmaA;
  v.sigma_s = kSigmaS;
  return v;
}

std::string density_name(double density) {
  const int e = int(std::lround(std::log10(density)));
  return "density_1e" + (e < 0 ? "m" + std::to_string(-e) : std::to_string(e));
}

void expect_plausible(const SceneDescription& d, double bound, const std::string& what) {
  const RenderResult r = render_with_variance(build_scene(d), 16);
  expect_finite(r, what);
  expect_lit(r, what);
  if (bound > 0) expect_below_bound(r, bound, what);
}

class MediaDensity : public ::testing::TestWithParam<double> {};

TEST_P(MediaDensity, GridBoxRendersLikeHomogeneousBox) {
  const double density = GetParam();
  SceneDescription a = lit_floor(), b = lit_floor();
  a.media.push_back({"fog", homogeneous_box(density, Vec3d(-0.7), Vec3d(0.7))});
  b.media.push_back({"grid", grid_box(density, Vec3d(-0.7), 1.4)});
  const std::string what = density_name(density);
  const double bound = kLightRadiance;  // the only emitter (stress_checks.h)
  expect_plausible(a, bound, what + " homogeneous");
  expect_plausible(b, bound, what + " grid");
  expect_same_image(build_scene(a), build_scene(b), what);
}

// A real VDB file: a ball of density falling off to its rim (NanoVDB
// sampling). Not at 1e5: its low-density rim shares majorant cells with the
// dense core, and delta tracking there costs ~ density_scale steps per unit
// (4 s per tiny image at 1e5; see README, findings).
class VdbBallDensity : public ::testing::TestWithParam<double> {};

TEST_P(VdbBallDensity, IsFiniteLitAndBounded) {
  const double density = GetParam();
  const TempDir dir;
  VdbMediumDesc v = vdb_ball(dir);
  v.density_scale = density;
  SceneDescription d = lit_floor();
  d.media.push_back({"ball", v});
  expect_plausible(d, kLightRadiance, density_name(density) + " vdb");
}

INSTANTIATE_TEST_SUITE_P(Decades, MediaDensity, ::testing::Values(1e-4, 1e-2, 1.0, 1e2, 1e5),
                         [](const auto& info) { return density_name(info.param); });
INSTANTIATE_TEST_SUITE_P(Decades, VdbBallDensity, ::testing::Values(1e-4, 1e-2, 1.0, 1e2, 1e4),
                         [](const auto& info) { return density_name(info.param); });

// The camera inside the medium: inside a homogeneous box and inside a grid
// box covering the same space render the same image.
TEST(MediaCamera, InsideGridRendersLikeInsideHomogeneousBox) {
  SceneDescription a = lit_floor(), b = lit_floor();
  a.media.push_back({"fog", homogeneous_box(0.3, Vec3d(-2), Vec3d(4))});
  b.media.push_back({"grid", grid_box(0.3, Vec3d(-2), 6.0, 9)});
  const double bound = kLightRadiance;
  expect_plausible(a, bound, "camera in homogeneous box");
  expect_plausible(b, bound, "camera in grid");
  expect_same_image(build_scene(a), build_scene(b), "camera inside a medium");
}

TEST(MediaCamera, InsideUnboundedDenseFogIsFinite) {
  SceneDescription d = lit_floor();
  HomogeneousMediumDesc everywhere = homogeneous_box(50.0, {}, {});
  everywhere.bounds.reset();
  d.media.push_back({"air", everywhere});
  // Optical depth 50 per unit: the camera sees little, but its own neighbourhood
  // may still scatter light; only finiteness and the bound are certain.
  const RenderResult r = render_with_variance(build_scene(d), 16);
  expect_finite(r, "unbounded dense fog");
  expect_below_bound(r, kLightRadiance, "unbounded dense fog");
}

// Lights inside a dense grid (optical depth ~ 1.4 per unit): a point light
// and a sphere light at the grid's centre render like the same light in the
// homogeneous twin.
void expect_light_inside_grid(double radius, const std::string& what) {
  SceneDescription a = lit_floor(), b = lit_floor();
  for (SceneDescription* d : {&a, &b}) {
    d->lights.clear();
    add_light(*d, PointLightDesc{{0, 0, 0}, Rgb(3.f), radius});
  }
  a.media.push_back({"fog", homogeneous_box(2.0, Vec3d(-0.7), Vec3d(0.7))});
  b.media.push_back({"grid", grid_box(2.0, Vec3d(-0.7), 1.4)});
  // A sphere light has radiance I / (pi r^2); a point light none to bound by.
  const double bound = radius > 0 ? 3.0 / (M_PI * radius * radius) : 0;
  expect_plausible(a, bound, what + " homogeneous");
  expect_plausible(b, bound, what + " grid");
  expect_same_image(build_scene(a), build_scene(b), what);
}

TEST(LightInsideVdb, PointLightRendersLikeInHomogeneousTwin) {
  expect_light_inside_grid(0.0, "point light in grid");
}
TEST(LightInsideVdb, SphereLightRendersLikeInHomogeneousTwin) {
  expect_light_inside_grid(0.1, "sphere light in grid");
}

// The same lights at the centre of the real VDB ball (density_scale 3:
// optical depth ~ 1.7 from the centre to the rim): finite, lit, bounded.
TEST(LightInsideVdb, PointAndSphereLightsInsideAVdbFile) {
  const TempDir dir;
  for (double radius : {0.0, 0.1}) {
    SceneDescription d = lit_floor();
    d.lights.clear();
    add_light(d, PointLightDesc{{0, 0, 0}, Rgb(3.f), radius});
    VdbMediumDesc v = vdb_ball(dir);
    v.density_scale = 3;
    d.media.push_back({"ball", v});
    expect_plausible(d, radius > 0 ? 3.0 / (M_PI * radius * radius) : 0,
                     "light of radius " + std::to_string(radius) + " in a VDB");
  }
}

// Regression test of the density 1e5 finding: 9 voxels in one 16-voxel cell.
// Trilinear sampling is zero beyond index 9 (active max + 1), so a ray
// through index x in [10, 15] (inside the cell, outside the support) gets no
// majorant segment, and one through the grid gets segments ending at 9.
TEST(MajorantGridSupport, WalkStopsAtTheTrilinearSupport) {
  const FunctionGrid grid(9, 1.0, {}, [](const Vec3&) { return 1.f; });
  const MajorantGrid majorants(grid, 16);
  ASSERT_EQ(majorants.cells_x(), 1);
  int outside = 0;
  majorants.walk({12, 4, -5}, {0, 0, 1}, 0, 20, [&](const MajorantSegment&) {
    ++outside;
    return true;
  });
  EXPECT_EQ(outside, 0);
  float end = 0;
  majorants.walk({-5, 4, 4}, {1, 0, 0}, 0, 30, [&](const MajorantSegment& s) {
    if (s.max_density > 0) end = std::max(end, s.t1);
    return true;
  });
  EXPECT_NEAR(end, 14.f, 1e-4f);  // x = 9 at t = 14
}

}  // namespace
}  // namespace vesper::test
