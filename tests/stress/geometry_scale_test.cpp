// Geometry at scales 1e-4 .. 1e6 and far from the origin: the same scene
// (quads, spheres, a mesh, a quad light, a point light, optionally fog)
// resized and moved renders the same image as its unscaled twin (per-tile
// Welch t-test, Sidak, alpha 0.01), finite and lit.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_transform.h"
#include "stress_checks.h"

namespace vesper::test {
namespace {

// The Cornell box with a point light and a small mesh (a tetrahedron), so
// that every kind of positional input is scaled.
SceneDescription base_scene(bool fog) {
  SceneDescription d = small_cornell(32, 32, 8);
  add_light(d, PointLightDesc{{0.5, 1.5, 0.5}, Rgb(0.5f)});
  MeshShapeDesc tet;
  tet.positions = {{0.3, 1.0, -0.6}, {0.8, 1.0, -0.6}, {0.55, 1.0, -0.1}, {0.55, 1.5, -0.4}};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  tet.source = "inline";
  d.shapes.push_back({tet, 0, {}});
  if (fog) {
    HomogeneousMediumDesc m;
    m.sigma_a = Rgb(0.1f);
    m.sigma_s = Rgb(0.6f);
    m.g = 0.3;
    m.bounds = BoxDesc{{-0.9, 0.1, -0.9}, {0.9, 1.2, 0.9}};
    d.media.push_back({"fog", m});
  }
  return d;
}

struct Placement {
  double scale;
  Vec3d offset;
  bool fog;
};

class GeometryScale : public ::testing::TestWithParam<Placement> {};

TEST_P(GeometryScale, RendersLikeTheUnscaledTwin) {
  const Placement p = GetParam();
  const SceneDescription twin = base_scene(p.fog);
  const Scene scaled = build_scene(transformed(twin, p.scale, p.offset));
  const std::string what = "scale " + std::to_string(p.scale) + " offset " +
                           std::to_string(p.offset.x) + (p.fog ? " fog" : "");
  const RenderResult r = render_with_variance(scaled, 8);
  expect_finite(r, what);
  expect_lit(r, what);
  expect_same_image(build_scene(twin), scaled, what);
}

const Vec3d kFar{1e6, -1e6, 1e6};
INSTANTIATE_TEST_SUITE_P(Decades, GeometryScale,
                         ::testing::Values(Placement{1e-4, {}, false}, Placement{1e-3, {}, false},
                                           Placement{1e-2, {}, false}, Placement{1e2, {}, false},
                                           Placement{1e4, {}, false}, Placement{1e6, {}, false},
                                           Placement{1.0, kFar, false},
                                           Placement{1e-2, kFar, false},
                                           Placement{1e6, kFar, false}, Placement{1e-4, {}, true},
                                           Placement{1e6, {}, true}, Placement{1.0, kFar, true}),
                         [](const auto& info) {
                           const Placement& p = info.param;
                           const int e = int(std::lround(std::log10(p.scale)));
                           return "scale_1e" +
                                  (e < 0 ? "m" + std::to_string(-e) : std::to_string(e)) +
                                  (p.offset.x != 0 ? "_moved_1e6" : "") + (p.fog ? "_fog" : "");
                         });

}  // namespace
}  // namespace vesper::test
