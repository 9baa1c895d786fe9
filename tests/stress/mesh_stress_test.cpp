// Degenerate and sliver triangles, and a camera inside a closed mesh.
// Twins: a rectangle cut into 2000 needle triangles renders like the same
// rectangle as one quad (no leaks between slivers, finite normals); a closed
// cube with a bright sky outside renders like the same cube with no sky (no
// light leaks in through edges or corners).
#include <gtest/gtest.h>

#include <cmath>

#include "stress_checks.h"

namespace vesper::test {
namespace {

// A back wall (x in [-1, 1], y in [0, 2], z = -1), lit by the small Cornell light.
SceneDescription wall_scene() {
  SceneDescription d = small_cornell(24, 24, 8);
  d.shapes.resize(2);  // floor and ceiling only: the wall comes from the test
  return d;
}

// The wall as `n` pairs of needle triangles: vertical strips 2/n wide, 2 tall.
MeshShapeDesc needle_wall(int n) {
  MeshShapeDesc m;
  m.source = "inline";
  for (int i = 0; i <= n; ++i) {
    const double x = -1 + 2.0 * i / n;
    m.positions.push_back({x, 0, -1});
    m.positions.push_back({x, 2, -1});
  }
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    const uint32_t a = 2 * i, b = a + 1, c = a + 2, e = a + 3;
    m.triangles.push_back({a, c, e});
    m.triangles.push_back({a, e, b});
  }
  return m;
}

TEST(Slivers, NeedleWallRendersLikeTheQuadWall) {
  SceneDescription quad = wall_scene(), needles = wall_scene();
  add_quad(quad, {-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, 0);
  needles.shapes.push_back({needle_wall(1000), 0, {}});  // 1e-3 x 2: aspect 2000
  const RenderResult r = render_with_variance(build_scene(needles), 8);
  expect_finite(r, "needle wall");
  expect_lit(r, "needle wall");
  expect_same_image(build_scene(quad), build_scene(needles), "needle wall vs quad");
}

// Degenerate triangles in view and in the light's path: zero area (repeated
// vertices, all three equal, collinear), 1e-9 thin slivers, a 1e-9 small
// triangle. Image and every AOV finite, lit, within the emitter bound.
TEST(Slivers, DegenerateTrianglesStayFiniteAndBounded) {
  SceneDescription d = small_cornell(32, 32, 8);
  MeshShapeDesc m;
  m.source = "inline";
  m.positions = {
      {-0.8, 1.0, 0.2},   {-0.8, 1.0, 0.2},       {0.8, 1.2, 0.2},         // repeated vertex
      {0.1, 0.5, 0.5},    {0.1, 0.5, 0.5},        {0.1, 0.5, 0.5},         // one point
      {-0.9, 0.2, 0.0},   {0.0, 1.1, 0.0},        {0.9, 2.0, 0.0},         // collinear
      {-0.9, 1.5, 0.3},   {0.9, 1.5, 0.3},        {0.0, 1.5 + 1e-9, 0.3},  // 1e-9 thin, horizontal
      {0.0, 0.1, 0.4},    {0.0, 1.9, 0.4},        {1e-9, 1.0, 0.4},        // 1e-9 thin, vertical
      {0.2, 1.0, 0.6},    {0.2 + 1e-9, 1.0, 0.6}, {0.2, 1.0 + 1e-9, 0.6},  // 1e-9 small
      {-0.5, 1.97, -0.2}, {0.5, 1.97, -0.2},      {0.0, 1.97, 0.2 - 1e-9}  // sliver under the light
  };
  for (uint32_t i = 0; i < 7; ++i) m.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  m.triangles.push_back({0, 0, 0});  // an index repeated
  d.shapes.push_back({m, 0, {}});
  const RenderResult r = render_with_variance(build_scene(d), 8);
  expect_finite(r, "degenerate triangles");
  expect_lit(r, "degenerate triangles");
  expect_below_bound(r, 17.0, "degenerate triangles");
}

// A closed cube mesh [-s, s]^3 (outward winding), a sphere light inside, and
// optionally a bright sky outside.
SceneDescription closed_cube(double s, bool sky) {
  SceneDescription d = empty_scene(24, 24, 8, 6);
  d.camera.from = Vec3d(0.3, -0.2, 0.7) * s;
  d.camera.to = Vec3d(-0.2, 0.1, -1) * s;
  d.camera.fov_degrees = 90;
  MeshShapeDesc cube;
  cube.source = "inline";
  for (int i = 0; i < 8; ++i)
    cube.positions.push_back({i & 1 ? s : -s, i & 2 ? s : -s, i & 4 ? s : -s});
  cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  d.shapes.push_back({cube, add_material(d, "white", DiffuseMaterialDesc{Rgb(0.7f)}), {}});
  add_light(d, PointLightDesc{Vec3d(0.2, 0.5, -0.3) * s, Rgb(float(s * s)), 0.1 * s});
  if (sky) add_light(d, EnvironmentLightDesc{Rgb(100.f), std::nullopt, "", 1, 0});
  return d;
}

void expect_cube_sealed(double s) {
  const std::string what = "cube of half-size " + std::to_string(s);
  const SceneDescription open_sky = closed_cube(s, true);
  const RenderResult r = render_with_variance(build_scene(open_sky), 8);
  expect_finite(r, what);
  expect_lit(r, what);
  // The sphere light's radiance I / (pi r^2) is the only one that may be seen.
  expect_below_bound(r, 1.0 / (M_PI * 0.01), what);
  expect_same_image(build_scene(closed_cube(s, false)), build_scene(open_sky), what);
}

TEST(InsideClosedMesh, LightOnlyFromTheInteriorLight) { expect_cube_sealed(1.0); }
TEST(InsideClosedMesh, LightOnlyFromTheInteriorLightAtScale1em3) { expect_cube_sealed(1e-3); }
TEST(InsideClosedMesh, LightOnlyFromTheInteriorLightAtScale1e4) { expect_cube_sealed(1e4); }

}  // namespace
}  // namespace vesper::test
