// Point and spot lights with a radius (sphere lights): the solid-angle
// sampling of the sphere (chi-square), the sampled points on the sphere, and
// convergence to the delta light as the radius goes to 0. The irradiance on
// a plane is checked in analytic_test.cpp.
#include <gtest/gtest.h>

#include "chi2.h"
#include "renderer/lights/light.h"
#include "renderer/lights/sphere_cone.h"
#include "renderer/sampling/sampler.h"

namespace vesper {
namespace {

constexpr double kAlpha = 0.01;

class SphereConeChi2 : public ::testing::TestWithParam<float> {};

TEST_P(SphereConeChi2, SamplingMatchesThePdf) {
  // A sphere of radius 1 seen from distance GetParam() (half-angle asin(1/d)).
  const Vec3 p(0.2f, -0.1f, 0.3f), center = p + normalize(Vec3(0.3f, 0.5f, -0.8f)) * GetParam();
  const auto cone = SphereCone::toward(p, center, 1.f);
  ASSERT_TRUE(cone);
  Sampler s(uint64_t(17));
  stats::Chi2Options opt;
  opt.pole = normalize(center - p);
  opt.theta_bins = 60;
  float worst = 0.f;  // of the sampled points' distance to the sphere
  const auto r = stats::chi2_test(
      [&]() -> std::optional<Vec3> {
        float t = 0.f;
        const Vec3 wi = cone->sample(s.next2(), &t);
        worst = std::max(worst, std::abs(length(p + wi * t - center) - 1.f));
        return wi;
      },
      [&](const Vec3& wi) -> double { return cone->contains(wi) ? cone->pdf() : 0.0; }, opt);
  EXPECT_GT(r.p_value, stats::sidak_alpha(kAlpha, 3)) << r.message;
  EXPECT_NEAR(r.pdf_integral, 1.0, 2e-2);  // the grid's cells straddle the cone's rim
  EXPECT_LT(worst, 1e-4f);
}
INSTANTIATE_TEST_SUITE_P(SeveralDistances, SphereConeChi2, ::testing::Values(1.05f, 1.6f, 4.f));

TEST(SphereLight, InsideTheSphereItGivesNoSample) {
  const PointLight light{Vec3(0.f), Rgb(1.f), 0.5f};
  EXPECT_FALSE(light.sample(Vec3(0.1f, 0.2f, 0.f), {0.5f, 0.5f}));
}

TEST(SphereLight, RadiusToZeroConvergesToThePointLight) {
  const Vec3 p(0.3f, -1.2f, 0.4f), c(0.1f, 0.5f, -0.2f);
  const Rgb intensity(2.f, 1.f, 0.5f);
  const auto delta = PointLight{c, intensity}.sample(p, {0.3f, 0.7f});
  ASSERT_TRUE(delta);
  double previous = 1e30;
  for (float radius : {0.3f, 0.03f, 3e-3f, 3e-4f}) {
    const auto s = PointLight{c, intensity, radius}.sample(p, {0.3f, 0.7f});
    ASSERT_TRUE(s);
    const double err =
        std::abs(s->radiance.r / delta->radiance.r - 1.0) + (1.0 - dot(s->wi, delta->wi));
    EXPECT_LT(err, previous) << "radius " << radius;
    previous = err;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST(SphereLight, SpotFalloffFollowsTheDirectionFromTheCentre) {
  SpotLight spot;
  spot.position = Vec3(0.f);
  spot.direction = Vec3(0, -1, 0);
  spot.intensity = Rgb(1.f);
  spot.cos_cone = std::cos(0.5f);
  spot.cos_falloff_start = std::cos(0.3f);
  spot.radius = 0.05f;
  EXPECT_TRUE(spot.sample(Vec3(0.f, -2.f, 0.f), {0.5f, 0.5f}));
  EXPECT_FALSE(spot.sample(Vec3(0.f, 2.f, 0.f), {0.5f, 0.5f}));  // behind the cone
  EXPECT_FALSE(Light(spot).bounds()->is_point());
}

}  // namespace
}  // namespace vesper
