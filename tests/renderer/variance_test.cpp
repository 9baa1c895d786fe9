// The per-pixel variance of the pixel mean (variance.R/G/B) predicts the
// spread of the pixel means across independent renders.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "renderer/render/render.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

// Means and predicted variances of the beauty R, G, B of many seeds' renders.
struct SeedRenders {
  int seeds = 0;
  size_t values = 0;                  // pixels * 3
  std::vector<std::vector<float>> m;  // [seed][pixel * 3 + c]
  std::vector<std::vector<float>> v;
};

SeedRenders render_seeds(const SceneDescription& d, int seeds) {
  const Scene scene = build_scene(d);
  SeedRenders out;
  out.seeds = seeds;
  for (int s = 0; s < seeds; ++s) {
    RenderOptions o;
    o.seed = uint64_t(1000 + s);
    o.aovs = std::vector<Aov>{Aov::Variance};
    const LayeredImage img = render(scene, o).image;
    const int r = img.channel_index("R"), vr = img.channel_index("variance.R");
    std::vector<float> m, v;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < 3; ++c) {
          m.push_back(img.at(x, y, size_t(r + c)));
          v.push_back(img.at(x, y, size_t(vr + c)));
        }
    out.values = m.size();
    out.m.push_back(std::move(m));
    out.v.push_back(std::move(v));
  }
  return out;
}

// Z statistic of H0 "E[predicted variance] = Var(pixel mean)" over the
// values in [first, last): per seed s, u_s = sum_i (m_si - mean_i)^2 S/(S-1)
// - scale * v_si has expectation 0 under H0 (scale = 1); the u_s are
// exchangeable sums over many pixels, so mean(u) / (sd(u) / sqrt(S)) is
// approximately standard normal.
double variance_z(const SeedRenders& r, size_t first, size_t last, double scale = 1) {
  const int S = r.seeds;
  std::vector<double> mean(last - first, 0);
  for (int s = 0; s < S; ++s)
    for (size_t i = first; i < last; ++i) mean[i - first] += r.m[size_t(s)][i] / S;
  std::vector<double> u(size_t(S), 0);
  for (int s = 0; s < S; ++s)
    for (size_t i = first; i < last; ++i) {
      const double d = r.m[size_t(s)][i] - mean[i - first];
      u[size_t(s)] += d * d * S / (S - 1) - scale * r.v[size_t(s)][i];
    }
  double mu = 0, var = 0;
  for (double x : u) mu += x / S;
  for (double x : u) var += (x - mu) * (x - mu) / (S - 1);
  return mu / std::sqrt(var / S);
}

// Four quadrants, each tested at alpha = 0.001 / 4 (Bonferroni): |Z| < 3.48.
constexpr double kZCritical = 3.48;

void expect_variance_predicts_spread(const SceneDescription& d, const char* label) {
  const SeedRenders r = render_seeds(d, 40);
  const size_t quarter = r.values / 4;
  for (int q = 0; q < 4; ++q) {
    const size_t first = size_t(q) * quarter, last = first + quarter;
    const double z = variance_z(r, first, last);
    EXPECT_LT(std::abs(z), kZCritical) << label << " quarter " << q << ": Z = " << z;
    // The test can tell: a variance off by a factor 2 either way is rejected.
    EXPECT_GT(std::abs(variance_z(r, first, last, 2.0)), kZCritical) << label << " quarter " << q;
    EXPECT_GT(std::abs(variance_z(r, first, last, 0.5)), kZCritical) << label << " quarter " << q;
  }
}

TEST(Variance, PredictsTheSpreadOfPixelMeansAcrossSeeds) {
  expect_variance_predicts_spread(small_cornell(24, 24, 16), "cornell 16 spp");
}

TEST(Variance, HoldsWhenTheSampleCountIsNotAMultipleOfTheStreams) {
  expect_variance_predicts_spread(small_cornell(24, 24, 10), "cornell 10 spp");
}

TEST(Variance, IsNonNegativeAndTheSppChannelCountsTheSamples) {
  SceneDescription d = small_cornell(16, 16, 8);
  const Scene scene = build_scene(d);
  RenderOptions o;
  o.aovs = std::vector<Aov>{Aov::Variance, Aov::Spp};
  const LayeredImage img = render(scene, o).image;
  const int vr = img.channel_index("variance.R"), spp = img.channel_index("spp");
  ASSERT_GE(vr, 0);
  ASSERT_GE(spp, 0);
  size_t positive = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      EXPECT_EQ(img.at(x, y, size_t(spp)), 8.f);
      EXPECT_GE(img.at(x, y, size_t(vr)), 0.f);
      positive += img.at(x, y, size_t(vr)) > 0;
    }
  EXPECT_GT(positive, size_t(img.width * img.height / 2));
}

}  // namespace
}  // namespace vesper::test
