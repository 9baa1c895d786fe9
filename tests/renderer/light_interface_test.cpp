// Every light type implements one interface (renderer/lights/light_interface.h).
// Mostly compile-time checks: a type that misses a method, or keeps another
// signature, is not a light; Light only holds lights and forwards to them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <type_traits>

#include "renderer/lights/light.h"

namespace vesper {
namespace {

static_assert(LightInterface<QuadLight>);
static_assert(LightInterface<PointLight>);
static_assert(LightInterface<SpotLight>);
static_assert(LightInterface<SunLight>);
static_assert(LightInterface<EnvironmentLight>);

// Everything but bounds().
struct LightWithoutBounds {
  std::optional<LightSample> sample(const Vec3&, Vec2) const { return std::nullopt; }
  float pdf(const Vec3&, float) const { return 0.f; }
  Rgb emitted(const Vec3&) const { return {}; }
  float power(float) const { return 0.f; }
};
// sample() without the reference point, as distant lights once had it.
struct LightWithOtherSample : LightWithoutBounds {
  std::optional<LightSample> sample(Vec2) const { return std::nullopt; }
  std::optional<LightBounds> bounds() const { return std::nullopt; }
};
static_assert(!LightInterface<LightWithoutBounds>);
static_assert(!LightInterface<LightWithOtherSample>);
static_assert(!std::is_constructible_v<Light, LightWithoutBounds>);

TEST(LightInterface, LightForwardsToTheTypeItHolds) {
  const SpotLight spot{{0, 2, 0}, {0, -1, 0}, Rgb(5.f), std::cos(0.5f), std::cos(0.3f)};
  const Light light = spot;
  const Vec3 p(0.1f, 0.f, 0.f);
  const auto a = light.sample(p, {0.3f, 0.7f}), b = spot.sample(p, {0.3f, 0.7f});
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->radiance, b->radiance);
  EXPECT_EQ(a->wi, b->wi);
  EXPECT_EQ(light.power(3.f), spot.power(3.f));
  EXPECT_EQ(light.pdf(a->wi, a->distance), 0.f);  // delta: no ray hits it
  EXPECT_TRUE(light.emitted(a->wi).is_black());
}

TEST(LightInterface, BoundsArePointsForPointLightsBoxesForQuadsNoneAtInfinity) {
  const auto point = Light(PointLight{{1, 2, 3}, Rgb(1.f)}).bounds();
  ASSERT_TRUE(point);
  EXPECT_TRUE(point->is_point());
  EXPECT_EQ(point->lo, Vec3(1, 2, 3));

  QuadLight quad;
  quad.corner = {1, 0, 0};
  quad.edge1 = {-2, 0, 0};
  quad.edge2 = {0, 0, 3};
  const auto box = Light(quad).bounds();
  ASSERT_TRUE(box);
  EXPECT_EQ(box->lo, Vec3(-1, 0, 0));
  EXPECT_EQ(box->hi, Vec3(1, 0, 3));
  EXPECT_FALSE(box->is_point());

  EXPECT_FALSE(Light(SunLight{}).bounds());
  EXPECT_FALSE(Light(EnvironmentLight{}).bounds());
}

}  // namespace
}  // namespace vesper
