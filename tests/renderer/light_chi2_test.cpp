// Chi-square tests of light sampling: the directions a light samples must be
// distributed as the density it reports (which MIS relies on).
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "chi2.h"
#include "light_fixtures.h"
#include "renderer/lights/light_sampler.h"
#include "renderer/sampling/sampler.h"

namespace vesper {
namespace {

constexpr int kTests = 6;
// Distant lights ignore the reference point and the distance.
constexpr float kInf = std::numeric_limits<float>::infinity();
const double kLevel = stats::sidak_alpha(0.01, kTests);

// Distance along wi from p to the quad, or < 0 when wi misses it.
float hit_quad(const QuadLight& q, const Vec3& p, const Vec3& wi) {
  const float denom = dot(wi, q.normal);
  if (std::abs(denom) < 1e-12f) return -1.f;
  const float t = dot(q.corner - p, q.normal) / denom;
  if (t <= 0.f) return -1.f;
  const Vec3 h = p + wi * t - q.corner;
  const float a = dot(h, q.edge1) / length_squared(q.edge1),
              b = dot(h, q.edge2) / length_squared(q.edge2);
  return (a >= 0.f && a <= 1.f && b >= 0.f && b <= 1.f) ? t : -1.f;
}

QuadLight make_quad(Vec3 corner, Vec3 e1, Vec3 e2) { return test::make_quad(corner, e1, e2, 1.f); }

void expect_quad_sampling_matches_pdf(const QuadLight& q, const Vec3& p) {
  Sampler s(uint64_t(12345));
  const Vec3 centre = q.corner + (q.edge1 + q.edge2) * 0.5f;
  stats::Chi2Options opt;
  opt.pole = normalize(centre - p);
  opt.theta_bins = 20;
  const auto r = stats::chi2_test(
      [&]() -> std::optional<Vec3> {
        const auto ls = q.sample(p, s.next2());
        if (!ls) return std::nullopt;
        return ls->wi;
      },
      [&](const Vec3& wi) -> double {
        const float t = hit_quad(q, p, wi);
        return t < 0.f ? 0.0 : q.pdf(wi, t);
      },
      opt);
  EXPECT_GT(r.p_value, kLevel) << r.message;
  EXPECT_NEAR(r.sampled_fraction, 1.0, 1e-9);
}

TEST(LightChi2, QuadLightSeenFromClose) {
  expect_quad_sampling_matches_pdf(make_quad({-1, 1, -1}, {2, 0, 0}, {0, 0, 2}),
                                   {0.2f, 0.6f, 0.1f});
}
TEST(LightChi2, QuadLightSeenObliquely) {
  expect_quad_sampling_matches_pdf(make_quad({-1, 1, -1}, {2, 0, 0}, {0, 0, 2}), {1.5f, 0.7f, 0.f});
}

TEST(LightChi2, SunDiskSamplesItsCone) {
  SunLight sun;
  sun.direction = normalize(Vec3(0.3f, 1.f, 0.2f));
  sun.cos_max = std::cos(0.35f);  // a large disk so the grid resolves it
  sun.frame = Frame::from_normal(sun.direction);
  Sampler s(uint64_t(99));
  stats::Chi2Options opt;
  opt.pole = sun.direction;
  opt.theta_bins = 40;
  const auto r =
      stats::chi2_test([&]() -> std::optional<Vec3> { return sun.sample({}, s.next2())->wi; },
                       [&](const Vec3& wi) -> double { return sun.pdf(wi, kInf); }, opt);
  EXPECT_GT(r.p_value, kLevel) << r.message;
}

EnvironmentLight random_environment(float rotation_deg) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const int w = 32, h = 16;
  std::vector<Rgb> px(size_t(w * h));
  for (auto& c : px) {
    const float v = u(rng);
    c = Rgb(v * v * 4.f, v, u(rng));  // skewed so importance sampling matters
  }
  px[size_t(3 * w + 5)] = Rgb(80.f);  // a "sun" texel
  EnvironmentLight env;
  env.map = EnvironmentLight::make_map(w, h, std::move(px));
  env.cos_rot = std::cos(radians(rotation_deg));
  env.sin_rot = std::sin(radians(rotation_deg));
  return env;
}

void expect_env_sampling_matches_pdf(const EnvironmentLight& env) {
  Sampler s(uint64_t(4242));
  stats::Chi2Options opt;
  opt.pole = {0.f, 1.f, 0.f};
  opt.theta_bins = 16;
  opt.phi_bins = 32;
  const auto r = stats::chi2_test(
      [&]() -> std::optional<Vec3> {
        const auto ls = env.sample({}, s.next2());
        if (!ls) return std::nullopt;
        return ls->wi;
      },
      [&](const Vec3& wi) -> double { return env.pdf(wi, kInf); }, opt);
  EXPECT_GT(r.p_value, kLevel) << r.message;
  EXPECT_NEAR(r.pdf_integral, 1.0, 1e-2);
}

TEST(LightChi2, EnvironmentMapImportanceSampling) {
  expect_env_sampling_matches_pdf(random_environment(0.f));
}
TEST(LightChi2, RotatedEnvironmentMapImportanceSampling) {
  expect_env_sampling_matches_pdf(random_environment(40.f));
}

TEST(LightChi2, EnvironmentSampleRadianceMatchesLookup) {
  // The radiance a sample reports must be the map's value in that direction.
  const EnvironmentLight env = random_environment(25.f);
  Sampler s(uint64_t(5));
  for (int i = 0; i < 10000; ++i) {
    const auto ls = env.sample({}, s.next2());
    ASSERT_TRUE(ls);
    EXPECT_EQ(ls->radiance, env.emitted(ls->wi)) << "sample " << i;
  }
}

}  // namespace
}  // namespace vesper

namespace vesper {
namespace {

TEST(LightSampler, HalfPowerHalfUniformOverEmittingLights) {
  std::vector<Light> lights;
  lights.push_back(PointLight{Vec3(0.f), Rgb(100.f)});  // power 400 pi
  lights.push_back(PointLight{Vec3(1.f), Rgb(1.f)});    // power 4 pi
  lights.push_back(PointLight{Vec3(2.f), Rgb(0.f)});    // switched off
  const LightSampler s(lights, 1.f);
  EXPECT_NEAR(s.pmf(0) + s.pmf(1) + s.pmf(2), 1.0, 1e-6);
  EXPECT_NEAR(s.pmf(0), 0.5 * 100.0 / 101.0 + 0.25, 1e-6);
  EXPECT_NEAR(s.pmf(1), 0.5 * 1.0 / 101.0 + 0.25, 1e-6);
  EXPECT_EQ(s.pmf(2), 0.f);
}

}  // namespace
}  // namespace vesper
