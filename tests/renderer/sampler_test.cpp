// The Sampler (renderer/sampling/sampler.h): uniform, stratified within a
// stream, independent across streams, and a pure function of its arguments.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "renderer/sampling/sample_streams.h"
#include "renderer/sampling/sampler.h"
#include "tests/renderer/chi2.h"

namespace vesper {
namespace {

constexpr uint64_t kSeed = 42;

// Slot `slot` (0-based) of sample `sample` of `pixel`, drawn with next2 (the
// slot seeds do not depend on how the earlier slots were drawn).
Vec2 slot2(uint64_t pixel, uint64_t sample, uint32_t slot, uint64_t seed = kSeed) {
  Sampler s(seed, pixel, sample);
  for (uint32_t i = 0; i < slot; ++i) s.next1();
  return s.next2();
}
float slot1(uint64_t pixel, uint64_t sample, uint32_t slot) {
  Sampler s(kSeed, pixel, sample);
  for (uint32_t i = 0; i < slot; ++i) s.next2();
  return s.next1();
}
uint64_t sample_of(int stream, uint64_t point) { return point * kSampleStreams + uint64_t(stream); }

double chi2_uniform(const std::vector<int>& counts, double n) {
  const double expected = n / double(counts.size());
  double chi2 = 0;
  for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
  return stats::chi2_p_value(chi2, int(counts.size()) - 1);
}

TEST(Sampler, IsAPureFunctionOfItsArguments) {
  Sampler a(7, 123, 45), b(7, 123, 45), c(7, 123, 46), d(8, 123, 45);
  for (int i = 0; i < 40; ++i) {
    const Vec2 u = a.next2(), v = b.next2(), w = c.next2(), x = d.next2();
    EXPECT_EQ(u.x, v.x);
    EXPECT_EQ(u.y, v.y);
    EXPECT_NE(u.x, w.x);
    EXPECT_NE(u.x, x.x);
  }
  EXPECT_EQ(a.dimension(), 40u);
}

// One sample per pixel: across pixels the values are independent, so the
// counts are multinomial and Pearson's chi-square applies. 1D marginals in 64
// bins, 2D in 16 x 16, for several slots and sample indices (streams and
// points); overall alpha = 0.001 (Sidak over the 36 tests).
TEST(Sampler, MarginalsAreUniformAcrossPixels) {
  constexpr int kPixels = 1 << 16;
  const std::array<uint32_t, 4> slots{0, 1, 7, 30};
  const std::array<uint64_t, 3> samples{0, 6, 1001};
  const double alpha = stats::sidak_alpha(0.001, int(slots.size() * samples.size()) * 3);
  for (uint32_t slot : slots)
    for (uint64_t sample : samples) {
      std::vector<int> x(64), y(64), xy(256), one(64);
      for (uint64_t p = 0; p < kPixels; ++p) {
        const Vec2 u = slot2(p, sample, slot);
        const float v = slot1(p, sample, slot);
        ASSERT_TRUE(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1 && v >= 0 && v < 1);
        ++x[size_t(u.x * 64)], ++y[size_t(u.y * 64)], ++one[size_t(v * 64)];
        ++xy[size_t(u.x * 16) * 16 + size_t(u.y * 16)];
      }
      const auto what = ::testing::Message() << "slot " << slot << ", sample " << sample;
      EXPECT_GT(chi2_uniform(x, kPixels), alpha) << what << " (next2 x)";
      EXPECT_GT(chi2_uniform(y, kPixels), alpha) << what << " (next2 y)";
      EXPECT_GT(chi2_uniform(xy, kPixels), alpha) << what << " (next2)";
      EXPECT_GT(chi2_uniform(one, kPixels), alpha) << what << " (next1)";
    }
}

// Points [begin, begin + 2^m) of a stream in a slot form a (0,m,2)-net: for
// every split m = a + b, each of the 2^a x 2^b cells holds exactly one point.
void expect_net(uint64_t pixel, int stream, uint32_t slot, uint64_t begin, int m) {
  const uint64_t n = uint64_t(1) << m;
  std::vector<Vec2> pts;
  for (uint64_t i = 0; i < n; ++i) pts.push_back(slot2(pixel, sample_of(stream, begin + i), slot));
  for (int a = 0; a <= m; ++a) {
    std::vector<int> cells(n);
    for (const Vec2& u : pts)
      ++cells[size_t(u.x * float(1 << a)) * size_t(n >> a) + size_t(u.y * float(n >> a))];
    ASSERT_TRUE(std::all_of(cells.begin(), cells.end(), [](int c) { return c == 1; }))
        << "pixel " << pixel << " stream " << stream << " slot " << slot << " points [" << begin
        << ", " << begin + n << ") split " << a << "+" << m - a;
  }
}

static_assert(Sampler::kLowDiscrepancySlots > 11, "the net tests below use slots up to 11");

TEST(Sampler, EveryPowerOfTwoPrefixOfAStreamIsANet) {
  for (uint64_t pixel : {0u, 12345u})
    for (int stream = 0; stream < kSampleStreams; ++stream)
      for (uint32_t slot : {0u, 2u, 9u})
        for (int m = 0; m <= 10; ++m) {
          expect_net(pixel, stream, slot, 0, m);
          expect_net(pixel, stream, slot, uint64_t(1) << m, m);  // the next block too
        }
}

TEST(Sampler, OneDimensionalSlotsAreStratified) {
  for (int stream = 0; stream < kSampleStreams; ++stream)
    for (uint32_t slot : {0u, 3u, 11u})
      for (int m = 0; m <= 12; ++m) {
        std::vector<int> cells(size_t(1) << m);
        for (uint64_t i = 0; i < cells.size(); ++i)
          ++cells[size_t(slot1(99, sample_of(stream, i), slot) * float(cells.size()))];
        ASSERT_TRUE(std::all_of(cells.begin(), cells.end(), [](int c) { return c == 1; }))
            << "stream " << stream << " slot " << slot << " first 2^" << m << " points";
      }
}

// Slots from Sampler::kLowDiscrepancySlots on are independent random
// numbers: within one stream their counts are multinomial (chi-square over
// 4096 points in 8 x 8 bins, for two such slots; alpha = 0.001 overall).
TEST(Sampler, LaterSlotsAreIndependentWithinAStream) {
  constexpr int kN = 4096;
  const double alpha = stats::sidak_alpha(0.001, 2);
  for (uint32_t slot : {Sampler::kLowDiscrepancySlots, Sampler::kLowDiscrepancySlots + 5}) {
    std::vector<int> cells(64);
    for (uint64_t i = 0; i < kN; ++i) {
      const Vec2 u = slot2(7, sample_of(1, i), slot);
      ++cells[size_t(u.x * 8) * 8 + size_t(u.y * 8)];
    }
    EXPECT_GT(chi2_uniform(cells, kN), alpha) << "slot " << slot;
  }
}

// A smooth integrand over three slots (a next2 and a next1) with a known mean.
double integrand(Sampler& s) {
  const Vec2 u = s.next2();
  const float w = s.next1();
  return std::exp(-2.0 * (u.x - 0.3) * (u.x - 0.3)) * (1.0 + u.y * u.y) + 0.5 * std::sin(3.0 * w);
}

// Per pixel, the mean of each stream over its first kPoints points.
constexpr int kPoints = 16;
constexpr int kPixels = 8192;
std::vector<std::array<double, kSampleStreams>> stream_means(uint64_t seed) {
  std::vector<std::array<double, kSampleStreams>> means(kPixels);
  for (uint64_t p = 0; p < kPixels; ++p)
    for (int k = 0; k < kSampleStreams; ++k) {
      double sum = 0;
      for (uint64_t i = 0; i < kPoints; ++i) {
        Sampler s(seed, p, sample_of(k, i));
        sum += integrand(s);
      }
      means[p][size_t(k)] = sum / kPoints;
    }
  return means;
}

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}
double variance_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return s / double(v.size() - 1);
}

// Independent streams have uncorrelated means across pixels: Fisher's z of
// the Pearson correlation of every pair of streams is N(0, 1/(n-3));
// two-sided, overall alpha = 0.001 (Sidak over the pairs).
TEST(Sampler, StreamMeansAreUncorrelated) {
  const auto means = stream_means(kSeed);
  const int pairs = kSampleStreams * (kSampleStreams - 1) / 2;
  const double alpha = stats::sidak_alpha(0.001, pairs);
  for (int a = 0; a < kSampleStreams; ++a)
    for (int b = a + 1; b < kSampleStreams; ++b) {
      std::vector<double> x, y;
      for (const auto& m : means) x.push_back(m[size_t(a)]), y.push_back(m[size_t(b)]);
      const double mx = mean_of(x), my = mean_of(y);
      double sxy = 0;
      for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my);
      const double r = sxy / double(x.size() - 1) / std::sqrt(variance_of(x) * variance_of(y));
      const double z = std::atanh(r) * std::sqrt(double(x.size()) - 3);
      EXPECT_GT(std::erfc(std::abs(z) / std::sqrt(2.0)), alpha)
          << "streams " << a << " and " << b << ": correlation " << r;
    }
}

// A stream's stratified points beat independent ones: the variance (across
// pixels) of the mean of kPoints points of one stream, over Var(f) / kPoints
// with Var(f) from 2^20 independent points (Sampler(key) slots). For this
// smooth integrand shuffled, digitally shifted nets give about 0.04 (fully
// Owen-scrambled ones about 0.01; the variance of such a ratio estimate over
// 8192 pixels is a few per cent of it); an iid sampler gives 1 +- 0.02. The
// bound 0.5 separates the two by far.
TEST(Sampler, AStreamMeanHasLowerVarianceThanIid) {
  std::vector<double> iid;
  for (uint64_t i = 0; i < (1u << 20); ++i) {
    Sampler s(mix64(i ^ 0x5eed));
    iid.push_back(integrand(s));
  }
  const double iid_variance_of_mean = variance_of(iid) / kPoints;
  const auto means = stream_means(kSeed);
  for (int k = 0; k < kSampleStreams; ++k) {
    std::vector<double> m;
    for (const auto& pm : means) m.push_back(pm[size_t(k)]);
    const double ratio = variance_of(m) / iid_variance_of_mean;
    EXPECT_LT(ratio, 0.5) << "stream " << k;
    RecordProperty("variance_ratio_stream_" + std::to_string(k), std::to_string(ratio));
  }
}

// What the film's variance estimate rests on: with independent streams, the
// spread of the K stream means, s^2 / K, is an unbiased estimate of the
// variance of the pixel mean. Its average over pixels against the variance of
// the pixel means across pixels (same integrand, independent scrambles per
// pixel): Z-test with both standard errors, two-sided, alpha = 0.001.
TEST(Sampler, StreamSpreadEstimatesTheVarianceOfThePixelMean) {
  const auto means = stream_means(kSeed + 1);
  std::vector<double> pixel_mean, estimate;
  for (const auto& m : means) {
    double mbar = 0;
    for (double v : m) mbar += v / kSampleStreams;
    double s2 = 0;
    for (double v : m) s2 += (v - mbar) * (v - mbar) / (kSampleStreams - 1);
    pixel_mean.push_back(mbar);
    estimate.push_back(s2 / kSampleStreams);
  }
  const double predicted = mean_of(estimate),
               predicted_se = std::sqrt(variance_of(estimate) / kPixels);
  const double actual = variance_of(pixel_mean);
  const double mu = mean_of(pixel_mean);
  double m4 = 0;
  for (double x : pixel_mean) m4 += std::pow(x - mu, 4) / kPixels;
  const double actual_se =
      std::sqrt((m4 - actual * actual * (kPixels - 3.0) / (kPixels - 1.0)) / kPixels);
  const double z = (predicted - actual) / std::hypot(predicted_se, actual_se);
  EXPECT_GT(std::erfc(std::abs(z) / std::sqrt(2.0)), 0.001)
      << "predicted " << predicted << " +- " << predicted_se << ", actual " << actual << " +- "
      << actual_se;
}

}  // namespace
}  // namespace vesper
