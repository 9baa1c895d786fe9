#pragma once
// The first two Sobol dimensions at a hash-shuffled point index: the padded
// (0,2)-sequence of Burley 2020 ("Practical Hash-based Owen Scrambling",
// JCGT 9(4)), kept in fixed point so that no bit reversal is needed per point.
// Hand-written: no Debian package provides such a generator.
//
// - Shuffle: the index is permuted by a nested uniform (Owen) scramble of
//   its bits from the top, so bit k of the result depends only on bits >= k
//   of the index: every aligned block of 2^m indices (in particular the first
//   2^m) maps onto an aligned block of 2^m, whatever m is.
// - Sobol dimension 0 (van der Corput) of index j is reverse_bits(j) read as
//   a 32-bit binary fraction. Given the index bit-reversed (bit 0 = its top
//   bit), the scramble's output is the shuffled index bit-reversed, i.e.
//   directly dimension 0 of the shuffled point.
// - Dimension 1 (generator matrix: Pascal's triangle mod 2) follows from
//   dimension 0 by a subset-sum transform (below). Any aligned block of 2^m
//   points of the pair is a (0,m,2)-net.
#include <cstdint>

namespace vesper {

constexpr uint32_t reverse_bits(uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x >> 4) & 0x0f0f0f0fu);
  x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
  return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}

// A hash-based nested uniform scramble: output bit k is input bit k flipped
// by a function of bits 0..k-1 and the seed (additions, odd multiplications
// and x ^= x * even never carry information downwards). Unlike the
// Laine-Karras permutation Burley uses, its seed-dependent multiplications
// make the flips of a bit under different lower bits unbiased and pairwise
// independent over random seeds, as a true Owen scramble's are
// (tests/renderer/shuffled_sobol_test.cpp; constants picked by that measurement).
constexpr uint32_t nested_scramble(uint32_t x, uint32_t seed) {
  x += seed;
  x *= (seed >> 15) | 1u;
  x ^= x * 0x0050febeu;
  x += seed >> 7;
  x *= (seed >> 9) | 1u;
  x ^= x * 0x878975d6u;
  return x;
}

// Sobol dimension 0 of the point at index reverse_bits(index_bits) after the
// shuffle by `seed`, as a 32-bit binary fraction.
constexpr uint32_t shuffled_sobol0(uint32_t index_bits, uint32_t seed) {
  return nested_scramble(index_bits, seed);
}

// Sobol dimension 1 of a point from its dimension 0 (both binary fractions).
// Digit t (bit 31 - t) of dimension 1 is the xor of the index bits k whose
// 5-bit position has t as a bit subset (Lucas' theorem); dimension 0 holds
// bit k at bit 31 - k, which turns that into a subset sum over bit positions,
// done in five butterfly steps.
constexpr uint32_t sobol1_from_sobol0(uint32_t x) {
  x ^= (x << 1) & 0xaaaaaaaau;
  x ^= (x << 2) & 0xccccccccu;
  x ^= (x << 4) & 0xf0f0f0f0u;
  x ^= (x << 8) & 0xff00ff00u;
  x ^= (x << 16) & 0xffff0000u;
  return x;
}

// A binary fraction -> float in [0, 1): its first 24 digits, never 1.0f.
constexpr float fraction_to_float(uint32_t x) { return float(x >> 8) * 0x1p-24f; }

}  // namespace vesper
