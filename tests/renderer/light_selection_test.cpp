// Light selection at a shading point (lights/light_sampler.h): the indices it
// draws follow the pmf it reports, lights that provably give nothing get no
// share while every other light keeps one, and renders with either selection
// match a closed-form irradiance (which a wrong MIS pmf breaks).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "analytic_plane.h"
#include "chi2.h"
#include "light_fixtures.h"
#include "minimal_scene.h"
#include "render_stats.h"
#include "renderer/lights/light_sampler.h"
#include "renderer/scene/scene_loader.h"
#include "scene_fixtures.h"

namespace vesper {
namespace {

using test::make_quad;

// Ten small candles on a grid, a quad facing down, a sun.
std::vector<Light> candle_lights() {
  std::vector<Light> lights;
  for (int i = 0; i < 10; ++i)
    lights.push_back(
        PointLight{Vec3(float(i % 5) - 2.f, 0.5f, float(i / 5) * 2.f - 1.f), Rgb(1.f), 0.05f});
  lights.push_back(make_quad(Vec3(-0.5f, 2.f, -0.5f), Vec3(1, 0, 0), Vec3(0, 0, 1), 2.f));
  SunLight sun;  // only its power matters here
  sun.direction = Vec3(0, 1, 0);
  sun.irradiance = Rgb(1.f);
  lights.push_back(sun);
  return lights;
}

TEST(LightSelection, DrawnIndicesFollowThePmf) {
  // Pearson chi-square of 200000 draws at a point near one candle, alpha = 0.01.
  const std::vector<Light> lights = candle_lights();
  const LightSampler s(lights, 10.f, LightSelection::Spatial);
  const ShadingPoint at{Vec3(-1.8f, 0.f, -0.9f), Vec3(0, 1, 0)};
  std::vector<double> expected(lights.size()), observed(lights.size(), 0.0);
  double sum = 0;
  for (size_t i = 0; i < lights.size(); ++i) sum += expected[i] = s.pmf(at, i);
  EXPECT_NEAR(sum, 1.0, 1e-5);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  constexpr int kDraws = 200000;
  for (int k = 0; k < kDraws; ++k) {
    float pmf = 0.f, u_rest = 0.f;
    LightSampler::Sums sums;
    const size_t i = s.sample(at, uniform(rng), &pmf, &u_rest, &sums);
    ASSERT_EQ(pmf, s.pmf(at, i));  // bit for bit: MIS recomputes it at the vertex
    // ... from the sums the choice kept, for every light a BSDF ray may hit.
    for (size_t j = 0; j < lights.size(); ++j) ASSERT_EQ(s.pmf(at, j, sums), s.pmf(at, j));
    ASSERT_GE(u_rest, 0.f);
    ASSERT_LT(u_rest, 1.f);
    observed[i] += 1;
  }
  double chi2 = 0;
  int bins = 0;
  for (size_t i = 0; i < lights.size(); ++i) {
    const double e = expected[i] * kDraws;
    ASSERT_GT(e, 5.0) << "light " << i;
    chi2 += (observed[i] - e) * (observed[i] - e) / e;
    ++bins;
  }
  EXPECT_GT(stats::chi2_p_value(chi2, bins - 1), 0.01) << "chi2 " << chi2;
  // The near candle takes the largest share, more than its base share.
  EXPECT_GT(expected[0], 2.0 * s.pmf(0));
}

TEST(LightSelection, TheUniformHalfGoesToFiniteLightsOnly) {
  // Lights at infinity are never close: they keep half their power share,
  // the finite lights split the uniform half (light_sampler.h).
  const std::vector<Light> lights = candle_lights();
  const LightSampler s(lights, 10.f, LightSelection::Spatial);
  double total = 0;
  for (const Light& l : lights) total += l.power(10.f);
  const size_t sun = lights.size() - 1;
  EXPECT_NEAR(s.pmf(sun), 0.5 * lights[sun].power(10.f) / total, 1e-6);
  for (size_t i = 0; i < sun; ++i)
    EXPECT_NEAR(s.pmf(i), 0.5 * lights[i].power(10.f) / total + 0.5 / double(sun), 1e-6);
  // With only lights at infinity the uniform half is theirs.
  const std::vector<Light> skies{lights[sun], EnvironmentLight{Rgb(0.01f), nullptr}};
  const LightSampler sky(skies, 10.f, LightSelection::Spatial);
  double sky_total = 0;
  for (const Light& l : skies) sky_total += l.power(10.f);
  EXPECT_NEAR(sky.pmf(1), 0.5 * skies[1].power(10.f) / sky_total + 0.25, 1e-6);
}

TEST(LightSelection, EquiangularChoiceFollowsItsPmfAmongAimableLights) {
  // Pearson chi-square of 200000 draws, alpha = 0.01: only the candles (one
  // point each) can be aimed at; their pmfs keep the base weights' ratios.
  const std::vector<Light> lights = candle_lights();
  const LightSampler s(lights, 10.f, LightSelection::Spatial);
  ASSERT_TRUE(s.has_aimable());
  const size_t candles = 10;
  EXPECT_EQ(s.pmf_aimable(candles), 0.f);      // the quad
  EXPECT_EQ(s.pmf_aimable(candles + 1), 0.f);  // the sun
  double candle_base = 0;
  for (size_t i = 0; i < candles; ++i) candle_base += s.pmf(i);
  std::vector<double> observed(lights.size(), 0.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  constexpr int kDraws = 200000;
  for (int k = 0; k < kDraws; ++k) {
    float pmf = 0.f, u_rest = 0.f;
    const size_t i = s.sample_aimable(uniform(rng), &pmf, &u_rest);
    ASSERT_LT(i, candles);
    ASSERT_EQ(pmf, s.pmf_aimable(i));
    observed[i] += 1;
  }
  double chi2 = 0;
  for (size_t i = 0; i < candles; ++i) {
    EXPECT_NEAR(s.pmf_aimable(i), s.pmf(i) / candle_base, 1e-5);
    const double e = s.pmf_aimable(i) * kDraws;
    chi2 += (observed[i] - e) * (observed[i] - e) / e;
  }
  EXPECT_GT(stats::chi2_p_value(chi2, int(candles) - 1), 0.01) << "chi2 " << chi2;
  // No light to aim at: none is offered.
  const LightSampler none({lights[candles], lights[candles + 1]}, 10.f, LightSelection::Spatial);
  EXPECT_FALSE(none.has_aimable());
  EXPECT_EQ(none.pmf_aimable(0), 0.f);
}

TEST(LightSelection, OnlyProvablyDarkLightsGetNothing) {
  std::vector<Light> lights;
  lights.push_back(PointLight{Vec3(0, 1, 0), Rgb(1.f)});      // above the surface
  lights.push_back(PointLight{Vec3(0, -1, 0), Rgb(1.f)});     // behind it
  lights.push_back(PointLight{Vec3(5, 0.01f, 0), Rgb(1.f)});  // just above the horizon
  lights.push_back(make_quad(Vec3(-1, 3, -1), Vec3(0, 0, 2), Vec3(2, 0, 0), 1.f));  // faces up
  lights.push_back(make_quad(Vec3(-1, 3, -1), Vec3(2, 0, 0), Vec3(0, 0, 2), 1.f));  // faces down
  lights.push_back(PointLight{Vec3(0, 1, 0), Rgb(0.f)});                            // switched off
  const LightSampler s(lights, 10.f, LightSelection::Spatial);
  const ShadingPoint surface{Vec3(0.f), Vec3(0, 1, 0)};
  EXPECT_GT(s.pmf(surface, 0), 0.f);
  EXPECT_EQ(s.pmf(surface, 1), 0.f);
  EXPECT_GT(s.pmf(surface, 2), 0.01f);  // the floor share, though it is far and grazing
  EXPECT_EQ(s.pmf(surface, 3), 0.f);
  EXPECT_GT(s.pmf(surface, 4), 0.f);
  EXPECT_EQ(s.pmf(surface, 5), 0.f);
  // In a medium (no normal) the light behind is back.
  EXPECT_GT(s.pmf(ShadingPoint{Vec3(0.f), Vec3(0.f)}, 1), 0.f);
}

}  // namespace
}  // namespace vesper

namespace vesper::test {
namespace {

// A diffuse plane y = 0 under a quad light, six small sphere candles (one
// below the plane) and a dim sun, rendered with `mode`: each 4x4 tile's mean
// must match rho/pi * E(x) (Lambert's polygon formula for the quad, I cos /
// d^2 for each candle wholly above the horizon, E cos for the sun) by a
// Sidak-corrected t-test at family-wise alpha = 0.01. The quad is hit by
// BSDF rays, so its MIS weight must use the pmf of the vertex they left.
void expect_plane_under_many_lights(LightSelection mode) {
  constexpr double rho = 0.6, L = 3.0, I = 0.4, E_sun = 0.5;
  SceneDescription d = empty_scene(24, 24, 8, 1);
  d.render.light_selection = mode;
  d.film.filter = FilterType::Box;
  d.camera.from = {0.1, 0.9, 0.2};
  d.camera.to = {0.1, 0, 0.2};
  d.camera.up = {0, 0, -1};
  d.camera.fov_degrees = 80;
  add_quad(d, {-50, 0, 50}, {100, 0, 0}, {0, 0, -100},
           add_material(d, "plane", DiffuseMaterialDesc{Rgb(float(rho))}));
  const Vec3d corner{-0.5, 1, -0.5}, e1{1, 0, 0}, e2{0, 0, 1};
  add_light(d, QuadLightDesc{corner, e1, e2, Rgb(float(L))});
  const std::array<Vec3d, 4> verts{corner, corner + e1, corner + e1 + e2, corner + e2};
  const std::array<Vec3d, 6> candles{{{-0.6, 0.2, -0.5},
                                      {0.5, 0.15, 0.6},
                                      {0.7, 0.3, -0.4},
                                      {-0.3, 0.25, 0.7},
                                      {3, 0.3, 3},
                                      {0.2, -0.3, 0.1}}};
  for (const Vec3d& c : candles) add_light(d, PointLightDesc{c, Rgb(float(I)), 0.02});
  // Tilted so that the quad light's shadow falls outside the view.
  const Vec3d sun = normalize(Vec3d(2, 1, 0));
  add_light(d, SunLightDesc{sun, Rgb(float(E_sun)), 0.5});
  const Scene scene = build_scene(d);
  auto irradiance = [&](const Vec3d& x) {
    double e = E_sun * sun.y + polygon_irradiance(x, {0, 1, 0}, verts, L);
    for (const Vec3d& c : candles)
      if (c.y > 0) e += I * (c.y - x.y) / std::pow(length(c - x), 3.0);
    return e;
  };
  expect_plane_tiles_match(scene, rho, irradiance, 16, 16);
}

TEST(LightSelection, SpatialChoiceMatchesTheAnalyticPlane) {
  expect_plane_under_many_lights(LightSelection::Spatial);
}
TEST(LightSelection, PowerUniformChoiceMatchesTheAnalyticPlane) {
  expect_plane_under_many_lights(LightSelection::PowerUniform);
}
TEST(LightSelection, TreeChoiceMatchesTheAnalyticPlane) {
  expect_plane_under_many_lights(LightSelection::Tree);
}

}  // namespace
}  // namespace vesper::test

namespace vesper::test {
namespace {

TEST(LightSelection, SceneKeyDefaultsToSpatialAndRefusesOtherNames) {
  nlohmann::json doc = minimal_scene();
  EXPECT_EQ(parse_scene(doc, "x.json").render.light_selection, LightSelection::Spatial);
  doc["render"]["light_selection"] = "power_uniform";
  EXPECT_EQ(parse_scene(doc, "x.json").render.light_selection, LightSelection::PowerUniform);
  doc["render"]["light_selection"] = "tree";
  EXPECT_EQ(parse_scene(doc, "x.json").render.light_selection, LightSelection::Tree);
  doc["render"]["light_selection"] = "nearest";
  try {
    parse_scene(doc, "x.json");
    FAIL() << "an unknown light_selection loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "/render/light_selection") << e.what();
  }
}

}  // namespace
}  // namespace vesper::test
