// Numerical stability (moved here from tests/renderer/ into the stress suite):
// the same scene at very different scales and far from
// the origin renders the same image within noise; degenerate input renders
// finite images.
#include <gtest/gtest.h>

#include "scene_transform.h"
#include "stress_checks.h"

namespace vesper::test {
namespace {

SceneDescription base_scene() {
  SceneDescription d = small_cornell(32, 32, 8);
  add_light(d, PointLightDesc{{0.5, 1.5, 0.5}, Rgb(0.5f)});
  return d;
}

void expect_same_image(const SceneDescription& a, const SceneDescription& b) {
  test::expect_same_image(build_scene(a), build_scene(b), "stability");
}

TEST(Stability, SceneScaledDownBy1e4RendersTheSame) {
  expect_same_image(base_scene(), transformed(base_scene(), 1e-4, {0, 0, 0}));
}
TEST(Stability, SceneScaledUpBy1e5RendersTheSame) {
  expect_same_image(base_scene(), transformed(base_scene(), 1e5, {0, 0, 0}));
}
TEST(Stability, SceneMoved1e5FromOriginRendersTheSame) {
  expect_same_image(base_scene(), transformed(base_scene(), 1.0, {1e5, -1e5, 1e5}));
}

bool all_finite(const LayeredImage& img) {
  for (float v : img.pixels)
    if (!std::isfinite(v)) return false;
  return true;
}

TEST(Stability, DegenerateGeometryAndExtremeRoughnessStayFinite) {
  SceneDescription d = small_cornell(32, 32, 8);
  d.render.aovs = {Aov::Albedo, Aov::Normal, Aov::Depth};
  // Degenerate triangles: zero area, repeated vertices, collinear, and one good one.
  MeshShapeDesc mesh;
  mesh.positions = {{0, 1, 0},     {0, 1, 0},        {0.2, 1.2, 0},    {0.4, 1.4, 0},
                    {0.6, 1.6, 0}, {-0.5, 0.5, 0.5}, {-0.2, 0.5, 0.5}, {-0.3, 0.8, 0.5}};
  mesh.triangles = {{0, 1, 2}, {2, 2, 2}, {2, 3, 4}, {5, 6, 7}};
  mesh.source = "inline";
  d.shapes.push_back({mesh, 0, {}});
  // Zero-area light.
  add_light(d, QuadLightDesc{{0, 1.5, 0}, {0, 0, 0}, {0, 0, 0.2}, Rgb(100.f)});
  // Every material at roughness 0 and 1.
  for (double r : {0.0, 1.0}) {
    const uint32_t cond = add_material(d, "c", ConductorMaterialDesc{r, Rgb(0.2f), Rgb(3.f)});
    const uint32_t diel = add_material(d, "d", DielectricMaterialDesc{1.5, r});
    const uint32_t prin = add_material(d, "p", PrincipledMaterialDesc{Rgb(0.5f), 0.5, r});
    const double x = r == 0 ? -0.6 : 0.6;
    add_sphere(d, {x, 1.4, 0.0}, 0.15, cond);
    add_sphere(d, {x, 1.0, 0.2}, 0.15, diel);
    add_sphere(d, {x, 0.6, 0.4}, 0.15, prin);
  }
  add_light(d, EnvironmentLightDesc{});
  const Scene scene = build_scene(d);
  const RenderResult r = render(scene);
  EXPECT_TRUE(all_finite(r.image));
  EXPECT_EQ(r.stats.nonfinite_samples, 0u);
}

}  // namespace
}  // namespace vesper::test
