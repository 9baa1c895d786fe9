// Equiangular sampling in grid (VDB-like) media: the distance-sampling
// density there is unknown, the MIS weights use a deterministic proxy of it
// (volume_tracking.h), and the image must still be unbiased (t-test against
// equiangular off) and less noisy near a point light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "equiangular_stats.h"
#include "renderer/integrator/light_vertex.h"
#include "scene_fixtures.h"
#include "test_grids.h"

namespace vesper::test {
namespace {

// A box of smoke filling the view, denser toward +y and lumpy along x
// (density 0.1 to 1.2 inside, no thin fringe where the medium is so rare
// that distance sampling would hardly ever scatter), over a floor.
SceneDescription grid_box_scene(int max_depth, float density_scale = 1.f) {
  SceneDescription d = empty_scene(24, 24, 64, max_depth);
  d.camera.from = {0, 0.3, 3.2};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 40;
  const uint32_t grey = add_material(d, "grey", DiffuseMaterialDesc{Rgb(0.5f)});
  add_quad(d, {-3, -1.25, 3}, {6, 0, 0}, {0, 0, -6}, grey);
  VdbMediumDesc v;
  v.file = "gradient";
  const int n = 17;
  v.density =
      std::make_shared<FunctionGrid>(n, 2.4 / (n - 1), Vec3d(-1.2, -1.2, -1.2), [n](const Vec3& p) {
        const Vec3 c = p / float(n - 1) - Vec3(0.5f);  // in [-0.5, 0.5]^3
        return 0.6f + c.y + 0.1f * std::sin(9.f * c.x);
      });
  // Thin at density_scale 1: about one mean free path across.
  v.sigma_s = Rgb(1.f, 0.8f, 0.6f) * density_scale;
  v.sigma_a = Rgb(0.1f) * density_scale;
  v.g = 0.3;
  MediumDesc& m = d.media.emplace_back();
  m.name = "gradient";
  m.medium = v;
  return d;
}

TEST(EquiangularGrid, PointLightInsideAGridMediumIsUnbiased) {
  SceneDescription d = grid_box_scene(4);
  add_light(d, PointLightDesc{{0.15, 0.1, 0.1}, Rgb(1.5f)});
  expect_on_and_off_agree(build_scene(d));
}

TEST(EquiangularGrid, SpotLightInAGridMediumIsUnbiased) {
  SceneDescription d = grid_box_scene(4);
  add_light(d, SpotLightDesc{{0.1, 1.2, 0.2}, normalize(Vec3d(0, -1, -0.1)), Rgb(8.f), 25, 20});
  expect_on_and_off_agree(build_scene(d));
}

TEST(EquiangularGrid, LightsOutOfReachInADenseGridMediumStayUnbiased) {
  // Ten times denser: most rays have the lights out of equiangular
  // sampling's reach (equiangular_reach.h), some near the front one do not;
  // both strategies must agree on which.
  SceneDescription d = grid_box_scene(4, 10.f);
  add_light(d, PointLightDesc{{0.15, 0.1, 0.1}, Rgb(1.5f)});
  add_light(d, PointLightDesc{{-0.3, 0.5, 1.0}, Rgb(1.f)});  // near the front face
  expect_on_and_off_agree(build_scene(d));
}

TEST(EquiangularGrid, PointLightInsideAGridMediumIsLessNoisy) {
  // Single scattering only, where equiangular sampling matters most.
  SceneDescription d = grid_box_scene(1);
  add_light(d, PointLightDesc{{0.15, 0.1, 0.1}, Rgb(1.5f)});
  const OnOffNoise noise = expect_on_and_off_agree(build_scene(d));
  EXPECT_LT(noise.se_on, 0.7 * noise.se_off);
}

// Light-vertex connections in a grid medium: their MIS weights use the same
// deterministic proxies, so the image must not change (t-test against the
// connections off).
TEST(LightVertexGrid, ConnectionsInAGridMediumAreUnbiased) {
  SceneDescription d = grid_box_scene(4);
  add_light(d, PointLightDesc{{0.15, 0.1, 0.1}, Rgb(1.5f)});
  add_light(d,
            SpotLightDesc{{0.1, 1.0, 0.2}, normalize(Vec3d(0, -1, -0.1)), Rgb(4.f), 25, 20, 0.1});
  RenderOptions on, off;
  on.light_vertices = true;
  off.light_vertices = false;
  expect_estimators_agree(build_scene(d), on, off);
}

// The default: connections where every medium is homogeneous or a light sits
// in a scattering medium (light_vertex.h says what was measured).
TEST(LightVertexGrid, DefaultFollowsWhereTheLightsSit) {
  SceneDescription inside = grid_box_scene(4);
  add_light(inside, PointLightDesc{{0.15, 0.1, 0.1}, Rgb(1.5f)});
  EXPECT_TRUE(light_vertices_pay_off(build_scene(inside)));
  SceneDescription outside = grid_box_scene(4);
  add_light(outside, PointLightDesc{{0.15, 2.0, 0.1}, Rgb(1.5f)});
  EXPECT_FALSE(light_vertices_pay_off(build_scene(outside)));
  SceneDescription fog = empty_scene(8, 8, 4, 4);
  add_light(fog, PointLightDesc{{0, 5, 0}, Rgb(1.f)});
  HomogeneousMediumDesc h;
  h.sigma_s = Rgb(0.1f);
  h.bounds = BoxDesc{{-1, -1, -1}, {1, 1, 1}};
  MediumDesc& m = fog.media.emplace_back();
  m.name = "fog";
  m.medium = h;
  EXPECT_TRUE(light_vertices_pay_off(build_scene(fog)));
}

}  // namespace
}  // namespace vesper::test
