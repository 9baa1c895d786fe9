// cone_interval: the part of a segment inside a spot light's cone, checked
// against a dense scan of the segment on random lines and cones.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "renderer/integrator/cone_interval.h"

namespace vesper::test {
namespace {

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> n;
  for (;;) {
    const Vec3 v{n(rng), n(rng), n(rng)};
    if (length(v) > 1e-3f) return normalize(v);
  }
}

TEST(ConeInterval, MatchesADenseScanOfTheSegment) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.f, 1.f);
  int with_interval = 0, without = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 apex = random_unit(rng) * (2.f * u01(rng));
    const Vec3 axis = random_unit(rng);
    const float cos_cone = 0.02f + 0.97f * u01(rng);
    const Vec3 o = random_unit(rng) * (3.f * u01(rng));
    // Half the lines aimed near the apex, so that many cross the cone.
    const Vec3 d = trial % 2 ? random_unit(rng) : normalize(apex + random_unit(rng) * 0.5f - o);
    const float ta = 4.f * u01(rng) - 2.f, tb = ta + 6.f * u01(rng);
    const auto in = cone_interval(o, d, apex, axis, cos_cone, ta, tb);
    (in ? with_interval : without)++;
    const int n = 4000;
    for (int i = 0; i <= n; ++i) {
      const float t = ta + (tb - ta) * float(i) / n;
      const Vec3 v = o + d * t - apex;
      const float margin = dot(v, axis) - cos_cone * length(v);
      if (std::abs(margin) < 1e-4f * (length(v) + 1e-3f)) continue;  // on the surface
      const bool inside = margin > 0.f;
      const bool in_interval = in && t >= in->t0 - 1e-5f && t <= in->t1 + 1e-5f;
      ASSERT_EQ(inside, in_interval)
          << "trial " << trial << " t " << t << " cos " << cos_cone << " interval "
          << (in ? in->t0 : -1.f) << ".." << (in ? in->t1 : -1.f);
    }
  }
  // Both outcomes must be exercised for the scan to mean anything.
  EXPECT_GT(with_interval, 400);
  EXPECT_GT(without, 100);
}

TEST(ConeInterval, WideConesAndUnboundedSegmentsKeepTheWholeSegment) {
  const auto wide = cone_interval({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, -0.2f, 0.5f, 3.f);
  ASSERT_TRUE(wide);
  EXPECT_EQ(wide->t0, 0.5f);
  EXPECT_EQ(wide->t1, 3.f);
  EXPECT_FALSE(cone_interval({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, 0.5f, 2.f, 1.f));
}

TEST(ConeInterval, AShaftSeenFromTheSide) {
  // A cone pointing down (-y) from (0, 2, 0), half-angle 45 degrees; the line
  // y = 0 along x crosses it over x in [-2, 2].
  const auto in = cone_interval({-5, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, -1, 0},
                                std::cos(3.14159265f / 4.f), 0.f, 10.f);
  ASSERT_TRUE(in);
  EXPECT_NEAR(in->t0, 3.f, 1e-4f);
  EXPECT_NEAR(in->t1, 7.f, 1e-4f);
}

}  // namespace
}  // namespace vesper::test
