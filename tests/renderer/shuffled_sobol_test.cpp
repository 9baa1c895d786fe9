// The building blocks of the sampler (renderer/sampling/shuffled_sobol.h):
// Sobol dimension 1, the nested (Owen) structure of the hash scramble, how
// close its random flips come to a true Owen scramble's, and the shuffle's
// block structure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "renderer/sampling/random_hash.h"
#include "renderer/sampling/shuffled_sobol.h"
#include "tests/renderer/chi2.h"

namespace vesper {
namespace {

// Sobol dimension 1 the textbook way: direction numbers v_0 = 1/2,
// v_{k+1} = v_k xor (v_k >> 1), xor-ed for the set bits of the index.
uint32_t sobol1_by_direction_numbers(uint32_t index) {
  uint32_t x = 0, v = 0x80000000u;
  for (; index; index >>= 1, v ^= v >> 1)
    if (index & 1u) x ^= v;
  return x;
}

TEST(ShuffledSobol, ReverseBitsIsAnInvolution) {
  EXPECT_EQ(reverse_bits(1u), 0x80000000u);
  EXPECT_EQ(reverse_bits(0x0000f00du), 0xb00f0000u);
  for (uint64_t i = 0; i < 10000; ++i) {
    const uint32_t x = uint32_t(mix64(i));
    ASSERT_EQ(reverse_bits(reverse_bits(x)), x);
  }
}

TEST(ShuffledSobol, Dimension1MatchesDirectionNumbers) {
  for (uint32_t i = 0; i < 4096; ++i)
    ASSERT_EQ(sobol1_from_sobol0(reverse_bits(i)), sobol1_by_direction_numbers(i)) << i;
  for (uint64_t i = 0; i < 10000; ++i) {
    const uint32_t x = uint32_t(mix64(i));
    ASSERT_EQ(sobol1_from_sobol0(reverse_bits(x)), sobol1_by_direction_numbers(x)) << x;
  }
}

// Nested: changing digit j never changes the digits above it (bits < j) and
// always flips digit j itself; so the scramble is a bijection that maps every
// elementary interval onto one of the same size.
TEST(ShuffledSobol, ScrambleIsNested) {
  for (uint64_t t = 0; t < 20000; ++t) {
    const uint32_t seed = uint32_t(mix64(2 * t));
    const uint32_t x = uint32_t(mix64(2 * t + 1));
    const uint32_t y = nested_scramble(x, seed);
    for (int j = 0; j < 32; ++j) {
      const uint32_t d = y ^ nested_scramble(x ^ (1u << j), seed);
      ASSERT_EQ(d & ((2u << j) - 1u), 1u << j) << "digit " << j;
    }
  }
}

// A true Owen scramble flips digit k under each prefix (the k digits above it)
// by an independent fair coin. Over many seeds, for digits k = 1..7 and every
// pair of prefixes, the two flips agree in half of the seeds (binomial Z-test,
// two-sided, overall alpha = 0.001 by Sidak over all pairs). The
// Laine-Karras permutation fails this badly (agreement 0.25 or 0.75 for some
// pairs); a scramble whose flips were shared across prefixes would too.
TEST(ShuffledSobol, FlipsUnderDifferentPrefixesAreIndependent) {
  constexpr int kSeeds = 4000, kMaxDigit = 7;
  int pairs = 0;
  for (int k = 1; k <= kMaxDigit; ++k) pairs += (1 << k) * ((1 << k) - 1) / 2;
  const double alpha = stats::sidak_alpha(0.001, pairs);
  for (int k = 1; k <= kMaxDigit; ++k) {
    const uint32_t prefixes = 1u << k;
    std::vector<std::vector<uint8_t>> flip(prefixes, std::vector<uint8_t>(kSeeds));
    for (int s = 0; s < kSeeds; ++s)
      for (uint32_t p = 0; p < prefixes; ++p)
        flip[p][size_t(s)] =
            uint8_t((nested_scramble(p, uint32_t(mix64(uint64_t(s) + 77))) >> k) & 1u);
    for (uint32_t a = 0; a < prefixes; ++a)
      for (uint32_t b = a + 1; b < prefixes; ++b) {
        int agree = 0;
        for (int s = 0; s < kSeeds; ++s) agree += flip[a][size_t(s)] == flip[b][size_t(s)];
        const double z = (agree - 0.5 * kSeeds) / std::sqrt(0.25 * kSeeds);
        ASSERT_GT(std::erfc(std::abs(z) / std::sqrt(2.0)), alpha)
            << "digit " << k << ", prefixes " << a << " and " << b << ": agree " << agree << "/"
            << kSeeds;
      }
  }
}

// The shuffle maps the indices [0, 2^m) onto an aligned block of 2^m indices
// (so every prefix of a stream is a block of Sobol points, hence a net).
TEST(ShuffledSobol, ShuffleMapsPrefixesOntoAlignedBlocks) {
  for (uint64_t t = 0; t < 200; ++t) {
    const uint32_t seed = uint32_t(mix64(t));
    for (int m = 0; m <= 12; ++m) {
      std::vector<bool> seen(size_t(1) << m);
      const uint32_t block = reverse_bits(shuffled_sobol0(0, seed)) >> m;
      for (uint32_t i = 0; i < (1u << m); ++i) {
        const uint32_t j = reverse_bits(shuffled_sobol0(reverse_bits(i), seed));
        ASSERT_EQ(j >> m, block) << "seed " << seed << ", m " << m << ", index " << i;
        ASSERT_FALSE(seen[j & ((1u << m) - 1u)]);
        seen[j & ((1u << m) - 1u)] = true;
      }
    }
  }
}

}  // namespace
}  // namespace vesper
