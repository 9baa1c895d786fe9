// Furnace tests: inside a uniform environment of radiance 1, an object that
// neither absorbs nor emits must be invisible: every pixel renders 1.
#include <gtest/gtest.h>

#include "render_stats.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

constexpr double kAlpha = 0.01;

SceneDescription furnace(MaterialDesc material) {
  SceneDescription d = empty_scene(32, 32, 16, 64);
  d.camera.from = {0, 0, 4};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = 30;
  const uint32_t m = add_material(d, "m", std::move(material));
  add_sphere(d, {0, 0, 0}, 1.0, m);
  add_light(d, EnvironmentLightDesc{});
  return d;
}

// Every 8x8 tile's mean must be 1 within the Sidak-corrected t bound.
void expect_furnace_is_one(const SceneDescription& d) {
  const Scene scene = build_scene(d);
  const TileStats st = tile_stats(scene, 12, 16, 8);
  const double crit = sidak_t_critical(kAlpha, int(st.mean.size()), st.batches - 1);
  for (size_t t = 0; t < st.mean.size(); ++t) {
    const double se = std::max(st.se[t], 1e-7);  // background tiles are exactly 1
    EXPECT_LT(std::abs(st.mean[t] - 1.0) / se, crit)
        << "tile " << t << " mean " << st.mean[t] << " se " << st.se[t];
  }
}

TEST(Furnace, WhiteDiffuseSphereVanishes) {
  expect_furnace_is_one(furnace(DiffuseMaterialDesc{Rgb(1.f)}));
}

TEST(Furnace, WhiteDiffuseSphereVanishesInAConstantEnvironmentMap) {
  // Same furnace through the image path: importance sampling of a lat-long
  // map (rotated) must still integrate to exactly 1.
  SceneDescription d = furnace(DiffuseMaterialDesc{Rgb(1.f)});
  EnvironmentLightDesc& env = std::get<EnvironmentLightDesc>(d.lights[0].light);
  env.image = EnvironmentImage{16, 8, std::vector<Rgb>(16 * 8, Rgb(1.f))};
  env.rotation = 33;
  expect_furnace_is_one(d);
}

TEST(Furnace, SmoothGlassSphereVanishes) {
  expect_furnace_is_one(furnace(DielectricMaterialDesc{1.5, 0.0}));
}

TEST(Furnace, RoughGlassSphereLosesOnlyMicrofacetEnergy) {
  // Single-scattering GGX loses energy at high roughness, so this is a bound,
  // not an equality: the sphere may darken but must never brighten.
  const Scene scene = build_scene(furnace(DielectricMaterialDesc{1.5, 0.3}));
  const TileStats st = tile_stats(scene, 12, 16, 8);
  const double crit = sidak_t_critical(kAlpha, int(st.mean.size()), st.batches - 1);
  for (size_t t = 0; t < st.mean.size(); ++t) {
    const double se = std::max(st.se[t], 1e-7);
    EXPECT_LT((st.mean[t] - 1.0) / se, crit) << "tile " << t << " brighter than the furnace";
    EXPECT_GT(st.mean[t], 0.85) << "tile " << t;
  }
}

TEST(Furnace, DiffuseSphereDetectsAnAbsorbingAlbedo) {
  // The same test must fail for a sphere that absorbs 2%: proves it has power.
  const Scene scene = build_scene(furnace(DiffuseMaterialDesc{Rgb(0.98f)}));
  const TileStats st = tile_stats(scene, 12, 16, 8);
  const double crit = sidak_t_critical(kAlpha, int(st.mean.size()), st.batches - 1);
  int rejected = 0;
  for (size_t t = 0; t < st.mean.size(); ++t)
    if (std::abs(st.mean[t] - 1.0) / std::max(st.se[t], 1e-7) > crit) ++rejected;
  EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace vesper::test
