// The statistics behind the comparison: Student's t tails and critical
// values, Holm's step-down, and tile tests on synthetic images whose noise is
// known (their Z must be standard normal when nothing changed).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "regress/holm.h"
#include "regress/student_t.h"
#include "regress/tile_statistics.h"

namespace vesper::regress {
namespace {

TEST(StudentT, TailsMatchTablesAndTheNormalLimit) {
  EXPECT_NEAR(two_sided_p_value(1.959963985, kInfiniteDof), 0.05, 1e-9);
  EXPECT_NEAR(two_sided_p_value(0, 5), 1.0, 1e-12);
  // Tables: t_{0.975}(10) = 2.228139, t_{0.995}(3) = 5.840909, t_{0.9995}(30) = 3.645959.
  EXPECT_NEAR(two_sided_p_value(2.228139, 10), 0.05, 1e-6);
  EXPECT_NEAR(two_sided_p_value(-5.840909, 3), 0.01, 1e-6);
  EXPECT_NEAR(two_sided_p_value(3.645959, 30), 0.001, 1e-7);
  // dof 1 is Cauchy: P(|T| > t) = 1 - 2 atan(t) / pi.
  EXPECT_NEAR(two_sided_p_value(3, 1), 1 - 2 * std::atan(3.0) / M_PI, 1e-12);
  EXPECT_NEAR(two_sided_p_value(4, 1e6), two_sided_p_value(4, kInfiniteDof), 1e-7);
  EXPECT_NEAR(two_sided_p_value(10, kInfiniteDof), std::erfc(10 / std::sqrt(2.0)), 1e-30);
}

TEST(StudentT, CriticalValuesInvertTheTail) {
  EXPECT_NEAR(two_sided_critical_value(0.05, kInfiniteDof), 1.959963985, 1e-8);
  EXPECT_NEAR(two_sided_critical_value(0.05, 10), 2.228139, 1e-6);
  EXPECT_NEAR(two_sided_critical_value(1e-4 / 16, kInfiniteDof), 4.5178, 1e-3);
  for (double dof : {2.0, 7.5, 100.0, kInfiniteDof})
    for (double p : {0.5, 1e-3, 1e-8}) {
      const double t = two_sided_critical_value(p, dof);
      EXPECT_NEAR(two_sided_p_value(t, dof) / p, 1, 1e-6) << "dof " << dof << " p " << p;
    }
}

TEST(Holm, StepsDownAndStopsAtTheFirstAcceptance) {
  // m = 4, alpha = 0.05: thresholds 0.0125, 0.0167, 0.025, 0.05 in p order.
  EXPECT_EQ(holm_rejections(std::vector<double>{0.01, 0.04, 0.03, 0.005}, 0.05),
            (std::vector<bool>{true, false, false, true}));
  EXPECT_EQ(holm_rejections(std::vector<double>{0.01, 0.02, 0.024, 0.001}, 0.05),
            (std::vector<bool>{true, true, true, true}));
  // The smallest fails alpha / m: nothing is rejected, even p values below alpha.
  EXPECT_EQ(holm_rejections(std::vector<double>{0.03, 0.04}, 0.05),
            (std::vector<bool>{false, false}));
  EXPECT_TRUE(holm_rejections(std::vector<double>{}, 0.05).empty());
  EXPECT_EQ(holm_rejections(std::vector<double>{NAN, 0.001}, 0.05),
            (std::vector<bool>{false, true}));
}

// A plane of `mean` plus Gaussian noise of variance `var` per pixel, the
// variance estimated from 4 streams (3 degrees of freedom) like the renderer's.
LumaPlane noisy_plane(int w, int h, double mean, double var, std::mt19937_64& rng) {
  LumaPlane p{w, h, {}, {}};
  std::normal_distribution<double> stream(0, std::sqrt(4 * var));
  for (int i = 0; i < w * h; ++i) {
    double s[4], m = 0;
    for (double& x : s) m += (x = mean + stream(rng)) / 4;
    double ss = 0;
    for (double x : s) ss += (x - m) * (x - m);
    p.value.push_back(m);
    p.variance.push_back(ss / 3 / 4);  // tau^2 / n with n = 4 streams of one sample
  }
  return p;
}

TEST(TileTests, ZIsStandardNormalWithoutChangeAndShowsAShift) {
  std::mt19937_64 rng(42);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int rep = 0; rep < 20; ++rep) {
    const TileGrid g =
        tile_tests(noisy_plane(64, 64, 0.5, 0.01, rng), noisy_plane(64, 64, 0.5, 0.01, rng), 16);
    ASSERT_EQ(g.tiles.size(), 16u);
    ASSERT_EQ(g.blocks.size(), 4u + 1u);  // 2x2 blocks of 32, then the frame
    for (const TileTest& t : g.tiles) {
      ASSERT_TRUE(t.tested);
      EXPECT_EQ(t.pixels, 256);
      EXPECT_GT(t.dof, 300);  // 2 x 256 pixels x 3, less for the estimates' spread
      sum += t.t;
      sum2 += t.t * t.t;
      ++n;
    }
  }
  EXPECT_NEAR(sum / n, 0, 4 / std::sqrt(double(n)));
  EXPECT_NEAR(sum2 / n, 1, 0.2);  // Var(Z) = 1: the variance model is right
  // A 10 % brighter tile: expected Z = 0.05 / sqrt(2 * 0.01 / 256) = 5.66.
  LumaPlane g = noisy_plane(64, 64, 0.5, 0.01, rng), f = noisy_plane(64, 64, 0.5, 0.01, rng);
  for (int y = 16; y < 32; ++y)
    for (int x = 32; x < 48; ++x) f.value[size_t(y) * 64 + size_t(x)] *= 1.10;
  const TileGrid grid = tile_tests(g, f, 16);
  const TileTest& t = grid.tiles[1 * 4 + 2];
  EXPECT_EQ(t.x, 32);
  EXPECT_EQ(t.y, 16);
  EXPECT_GT(t.t, 5.66 - 3);
  EXPECT_LT(t.t, 5.66 + 3);
  EXPECT_NEAR(relative_change(t.golden_mean, t.new_mean), 0.10, 0.03);
}

TEST(TileTests, EdgeTilesAreClippedAndSingleTileBlocksDropped) {
  std::mt19937_64 rng(7);
  const TileGrid g =
      tile_tests(noisy_plane(40, 20, 1, 0.01, rng), noisy_plane(40, 20, 1, 0.01, rng), 16);
  ASSERT_EQ(g.tiles_x, 3);
  ASSERT_EQ(g.tiles_y, 2);
  EXPECT_EQ(g.tiles[2].width, 8);
  EXPECT_EQ(g.tiles[5].height, 4);
  EXPECT_EQ(g.tiles[5].pixels, 8 * 4);
  // Level 1: 2x1 blocks of 32 (the right one holds tiles 2 and 5); level 2: the frame.
  ASSERT_EQ(g.blocks.size(), 3u);
  EXPECT_EQ(g.blocks[1].x, 32);
  EXPECT_EQ(g.blocks[1].width, 8);
  EXPECT_EQ(g.blocks[1].pixels, 8 * 20);
  EXPECT_EQ(g.blocks[2].pixels, 40 * 20);
}

TEST(TileTests, NoiselessTilesFlagRealDifferencesButNotRounding) {
  LumaPlane g{16, 16, std::vector<double>(256, 2.0), std::vector<double>(256, 0.0)};
  LumaPlane f = g;
  for (double& v : f.value) v = std::nextafter(float(v), 3.f);  // one float ulp
  EXPECT_LT(std::abs(tile_tests(g, f, 16).tiles[0].t), 1);
  for (double& v : f.value) v = 2.002;
  EXPECT_GT(tile_tests(g, f, 16).tiles[0].t, 100);
}

TEST(TileTests, NonFinitePixelsAreLeftOutOfBoth) {
  std::mt19937_64 rng(3);
  LumaPlane g = noisy_plane(16, 16, 1, 0.01, rng), f = noisy_plane(16, 16, 1, 0.01, rng);
  f.value[5] = NAN;
  g.variance[7] = INFINITY;
  const TileTest t = tile_tests(g, f, 16).tiles[0];
  EXPECT_EQ(t.pixels, 254);
  EXPECT_TRUE(std::isfinite(t.t));
}

}  // namespace
}  // namespace vesper::regress
