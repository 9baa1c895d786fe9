// The light tree (lights/light_tree.h) through LightSampler: its pmfs sum to
// one where no light is provably dark, the lights it draws follow the pmf it
// reports (chi-square), it never draws a light that provably gives nothing,
// its merged emission cones hold their children's, and a render with it
// agrees with one by power_uniform (t-test).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "chi2.h"
#include "estimator_agreement.h"
#include "light_fixtures.h"
#include "renderer/lights/light_sampler.h"
#include "renderer/lights/light_tree.h"
#include "renderer/math/frame.h"
#include "renderer/scene/scene.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

using Rng = std::mt19937_64;

float uniform(Rng& rng, float lo = 0.f, float hi = 1.f) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}
Vec3 random_direction(Rng& rng) {
  const float z = uniform(rng, -1.f, 1.f), phi = uniform(rng, 0.f, 2.f * kPi);
  const float r = std::sqrt(std::max(0.f, 1.f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}
Vec3 random_point(Rng& rng, float y_lo, float y_hi) {
  return {uniform(rng, -5.f, 5.f), uniform(rng, y_lo, y_hi), uniform(rng, -5.f, 5.f)};
}

// `n` lights over a 10 x 10 area at heights 0.5 to 3, cycling through point,
// sphere, spot (pointing anywhere) and quad (facing anywhere) unless
// `isotropic` (points and spheres only), with powers over two decades; and
// a sun.
std::vector<Light> scattered_lights(int n, uint64_t seed, bool isotropic) {
  Rng rng(seed);
  std::vector<Light> lights;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = random_point(rng, 0.5f, 3.f);
    const float intensity = std::pow(10.f, uniform(rng, -1.f, 1.f));
    switch (isotropic ? i % 2 : i % 4) {
      case 0:
        lights.push_back(PointLight{p, Rgb(intensity), 0.f});
        break;
      case 1:
        lights.push_back(PointLight{p, Rgb(intensity), 0.05f});
        break;
      case 2:
        lights.push_back(make_spot(p, random_direction(rng), intensity, 40.f, 30.f));
        break;
      default: {
        const Vec3 d = random_direction(rng);
        const Vec3 e1 = normalize(cross(d, std::abs(d.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
        lights.push_back(make_quad(p, e1 * 0.2f, cross(d, e1) * 0.2f, intensity));
      }
    }
  }
  SunLight sun;
  sun.direction = Vec3(0, 1, 0);
  sun.irradiance = Rgb(1.f);
  lights.push_back(sun);
  return lights;
}

TEST(LightTree, PmfSumsToOneWhereNoLightIsProvablyDark) {
  // Isotropic lights above the floor: at floor points (normal up) and at
  // points in a medium nothing is a proof of zero, so no walk dead-ends.
  const std::vector<Light> lights = scattered_lights(200, 1, true);
  const LightSampler s(lights, 20.f, LightSelection::Tree);
  ASSERT_TRUE(s.uses_tree());
  Rng rng(2);
  for (int k = 0; k < 40; ++k) {
    const ShadingPoint at{random_point(rng, k % 2 ? 0.f : -1.f, k % 2 ? 0.f : 4.f),
                          k % 2 ? Vec3(0, 1, 0) : Vec3(0.f)};
    double sum = 0;
    for (size_t i = 0; i < lights.size(); ++i) sum += s.pmf(at, i);
    EXPECT_NEAR(sum, 1.0, 1e-5) << "point " << k;
  }
}

TEST(LightTree, CoincidentLightsAndLightsAtInfinityAlone) {
  // 100 lights at one point still make a balanced tree (median splits).
  std::vector<Light> lights(100, Light(PointLight{Vec3(1, 2, 3), Rgb(1.f), 0.f}));
  const LightSampler s(lights, 10.f, LightSelection::Tree);
  const ShadingPoint at{Vec3(0.f), Vec3(0, 1, 0)};
  double sum = 0;
  for (size_t i = 0; i < lights.size(); ++i) sum += s.pmf(at, i);
  EXPECT_NEAR(sum, 1.0, 1e-5);
  std::vector<LightTree::Item> items;
  for (size_t i = 0; i < lights.size(); ++i) items.push_back({i, *lights[i].bounds(), 1.f});
  EXPECT_LE(LightTree(items, lights.size()).depth(), 7u);  // ceil(log2(100))
  // Only a sun: the tree is empty and the sun takes every choice.
  SunLight sun;
  sun.direction = Vec3(0, 1, 0);
  sun.irradiance = Rgb(1.f);
  const LightSampler only_sun({Light(sun)}, 10.f, LightSelection::Tree);
  float pmf = 0.f, u_rest = 0.f;
  EXPECT_EQ(only_sun.sample(at, 0.7f, &pmf, &u_rest), 0u);
  EXPECT_EQ(pmf, 1.f);
  EXPECT_EQ(only_sun.pmf(at, 0), 1.f);
}

// Pearson chi-square of `draws` choices at `at` against pmf(at, i), with one
// more cell for "no light" (a walk that found every light below provably
// dark) expected 1 - sum of the pmfs. Every draw's pmf must be pmf(at, i)
// bit for bit, also through the sums API. Returns the p-value.
double chi2_of_choices(const LightSampler& s, size_t lights, const ShadingPoint& at, int draws,
                       Rng& rng) {
  std::vector<double> expected(lights + 1), observed(lights + 1, 0.0);
  double sum = 0;
  for (size_t i = 0; i < lights; ++i) sum += expected[i] = double(s.pmf(at, i)) * draws;
  expected[lights] = std::max(0.0, draws - sum);
  for (int k = 0; k < draws; ++k) {
    float pmf = 0.f, u_rest = 0.f;
    LightSampler::Sums sums;
    const size_t i = s.sample(at, uniform(rng), &pmf, &u_rest, &sums);
    EXPECT_GE(u_rest, 0.f);
    EXPECT_LT(u_rest, 1.f);
    if (!(pmf > 0.f)) {
      observed[lights] += 1;
      continue;
    }
    if (pmf != s.pmf(at, i) || pmf != s.pmf(at, i, sums)) {
      ADD_FAILURE() << "light " << i << ": drawn with pmf " << pmf << ", pmf() says "
                    << s.pmf(at, i);
      return 0.0;
    }
    observed[i] += 1;
  }
  // Cells expected below 5 pooled into one (a cell expected 0 must stay empty).
  double chi2 = 0, pool_e = 0, pool_o = 0;
  int cells = 0;
  for (size_t i = 0; i <= lights; ++i) {
    if (expected[i] == 0.0) {
      EXPECT_EQ(observed[i], 0.0) << "cell " << i << " has pmf 0";
    }
    if (expected[i] < 5.0) {
      pool_e += expected[i];
      pool_o += observed[i];
      continue;
    }
    chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pool_e >= 5.0) {
    chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
    ++cells;
  }
  return stats::chi2_p_value(chi2, cells - 1);
}

TEST(LightTree, DrawnLightsFollowThePmf) {
  // 200 lights of four types and a sun; a floor point, a wall point and a
  // medium point; family-wise alpha = 0.001 (Sidak over the points).
  const std::vector<Light> lights = scattered_lights(200, 3, false);
  const LightSampler s(lights, 20.f, LightSelection::Tree);
  const ShadingPoint points[] = {{Vec3(0.5f, 0.f, -1.f), Vec3(0, 1, 0)},
                                 {Vec3(-5.f, 1.5f, 2.f), Vec3(1, 0, 0)},
                                 {Vec3(2.f, 1.f, 3.f), Vec3(0.f)}};
  const double alpha = stats::sidak_alpha(0.001, 3);
  Rng rng(4);
  for (const ShadingPoint& at : points)
    EXPECT_GT(chi2_of_choices(s, lights.size(), at, 400000, rng), alpha)
        << "at " << at.p.x << " " << at.p.y << " " << at.p.z;
}

TEST(LightTree, ProvablyDarkLightsAreNeverChosen) {
  std::vector<Light> lights = scattered_lights(120, 5, false);
  const size_t first = lights.size();
  lights.push_back(PointLight{Vec3(0.2f, -1.f, 0.f), Rgb(5.f), 0.1f});         // under the floor
  lights.push_back(make_spot(Vec3(0, 2, 0), Vec3(0, 1, 0), 5.f, 40.f, 30.f));  // shines up
  lights.push_back(make_quad(Vec3(-1, 3, -1), Vec3(0, 0, 2), Vec3(2, 0, 0), 5.f));  // faces up
  lights.push_back(PointLight{Vec3(9, 0.05f, 0), Rgb(0.01f), 0.f});  // grazing, dim, far
  const LightSampler s(lights, 20.f, LightSelection::Tree);
  const ShadingPoint floor{Vec3(0.f), Vec3(0, 1, 0)};
  for (size_t i = first; i < first + 3; ++i) EXPECT_EQ(s.pmf(floor, i), 0.f) << "light " << i;
  // The count walk's floor keeps every light that may reach: >= kFloor / N of the tree's share.
  EXPECT_GT(s.pmf(floor, first + 3), LightTree::kFloor * 0.5f / float(lights.size()) * 0.5f);
  Rng rng(6);
  for (int k = 0; k < 100000; ++k) {
    float pmf = 0.f, u_rest = 0.f;
    const size_t i = s.sample(floor, uniform(rng), &pmf, &u_rest);
    if (pmf > 0.f) {
      ASSERT_TRUE(i < first || i == first + 3 || i == lights.size() - 1) << i;
    }
  }
  // In a medium the light under the floor is back.
  EXPECT_GT(s.pmf(ShadingPoint{Vec3(0.f), Vec3(0.f)}, first), 0.f);
}

TEST(LightTree, MergedConesHoldBothCones) {
  // Directions on the rims of two random cones lie in their merged cone (to
  // 1e-5 in cosine, well inside light_importance's 1e-4 slack); the boxes
  // are unioned.
  Rng rng(7);
  for (int k = 0; k < 20000; ++k) {
    LightBounds a, b;
    a.lo = a.hi = random_point(rng, 0, 1);
    b.lo = b.hi = random_point(rng, 0, 1);
    a.axis = random_direction(rng);
    b.axis = k % 3 == 0 ? a.axis : random_direction(rng);  // equal axes are common (grids)
    a.cos_cone = std::cos(uniform(rng, 0.f, kPi * 0.99f));
    b.cos_cone = std::cos(uniform(rng, 0.f, kPi * 0.99f));
    const LightBounds m = merge_light_bounds(a, b);
    EXPECT_EQ(m.lo, min(a.lo, b.lo));
    EXPECT_EQ(m.hi, max(a.hi, b.hi));
    if (!(m.cos_cone > -1.f)) continue;  // the whole sphere holds anything
    for (const LightBounds* c : {&a, &b}) {
      const Frame f = Frame::from_normal(c->axis);
      const float sin_c = std::sqrt(std::max(0.f, 1.f - c->cos_cone * c->cos_cone));
      for (int j = 0; j < 16; ++j) {
        const float phi = 2.f * kPi * float(j) / 16.f;
        const Vec3 d = f.to_world({sin_c * std::cos(phi), sin_c * std::sin(phi), c->cos_cone});
        ASSERT_GE(dot(d, m.axis), m.cos_cone - 1e-5f) << "pair " << k;
      }
    }
  }
}

TEST(LightTree, SpatialSwitchesToTheTreeAboveTheThreshold) {
  std::vector<Light> lights;
  for (size_t i = 0; i < LightSampler::kTreeThreshold; ++i)
    lights.push_back(PointLight{Vec3(float(i), 1.f, 0.f), Rgb(1.f)});
  EXPECT_FALSE(LightSampler(lights, 10.f).uses_tree());
  lights.push_back(PointLight{Vec3(-1.f, 1.f, 0.f), Rgb(1.f)});
  EXPECT_TRUE(LightSampler(lights, 10.f).uses_tree());
  EXPECT_FALSE(LightSampler(lights, 10.f, LightSelection::PowerUniform).uses_tree());
  EXPECT_TRUE(LightSampler({lights[0]}, 10.f, LightSelection::Tree).uses_tree());
}

// A floor under an 8 x 8 grid of lights (sphere candles, spots shining down,
// small quads facing down), a partition and a floating slab throwing
// shadows: rendered with the tree and with power_uniform, every 6 x 6
// tile's mean must agree (Welch t-test, Sidak over the tiles, alpha 0.01).
TEST(LightTree, RenderAgreesWithPowerUniform) {
  SceneDescription d = empty_scene(24, 24, 16, 3);
  d.camera.from = {0, 6, 0.1};
  d.camera.to = {0, 0, 0};
  d.camera.up = {0, 0, -1};
  d.camera.fov_degrees = 70;
  const uint32_t grey = add_material(d, "grey", DiffuseMaterialDesc{Rgb(0.6f)});
  add_quad(d, {-6, 0, 6}, {12, 0, 0}, {0, 0, -12}, grey);
  add_quad(d, {0.3, 0, -4}, {0, 1.5, 0}, {0, 0, 8}, grey);   // partition
  add_quad(d, {-2, 1.2, -1}, {1.5, 0, 0}, {0, 0, 2}, grey);  // slab (two-sided)
  for (int i = 0; i < 64; ++i) {
    const Vec3d p{-3.5 + double(i % 8), 1.6 + 0.1 * double(i % 3), -3.5 + double(i / 8)};
    const float power = 0.2f + 0.3f * float(i % 5);
    if (i % 3 == 0)
      add_light(d, PointLightDesc{p, Rgb(power), 0.03});
    else if (i % 3 == 1)
      add_light(d, SpotLightDesc{p, {0.3, -1, 0}, Rgb(power), 35, 25, 0});
    else
      add_light(d, QuadLightDesc{p, {0.3, 0, 0}, {0, 0, 0.3}, Rgb(power * 3)});  // faces down
  }
  SceneDescription by_power = d;
  d.render.light_selection = LightSelection::Tree;
  by_power.render.light_selection = LightSelection::PowerUniform;
  const Scene tree = build_scene(d), power = build_scene(by_power);
  ASSERT_TRUE(tree.light_sampler.uses_tree());
  RenderOptions o;
  o.spp = 128;
  const EstimatorNoise noise = expect_estimators_agree(tree, o, power, o, 10, 6);
  EXPECT_GT(noise.se_b, 0.0);  // the lights reach the film
}

}  // namespace
}  // namespace vesper::test
