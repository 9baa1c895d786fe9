#pragma once
// The first two dimensions of the Sobol sequence, Owen-scrambled by hashing
// (after Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)).
// Hand-written: no Debian package provides an Owen-scrambled Sobol sequence.
//
// Digits are kept bit-reversed ("digit order"): bit 0 holds the most
// significant binary digit of a coordinate. In that order a nested uniform
// (Owen) scramble is a bijection whose output bit k is input bit k flipped by
// a random function of bits 0..k-1 (the digits above it): additions, odd
// multiplications and x ^= x * even never carry information downwards, so
// they build such a bijection from a seed.
#include <cstdint>

namespace vesper {

constexpr uint32_t reverse_bits(uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x >> 4) & 0x0f0f0f0fu);
  x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
  return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}

// A hash-based nested uniform scramble of digits in digit order. Compared
// with the Laine-Karras permutation Burley uses, the seed-dependent
// multiplications remove its correlations: over random seeds, the flips of a
// digit under any two different prefixes (and under xor-quadruples of
// prefixes) are unbiased within sampling noise for the top ten digits, as a
// true Owen scramble's are (constants picked by that measurement).
constexpr uint32_t owen_permute_digits(uint32_t x, uint64_t seed) {
  x += uint32_t(seed);
  x ^= x * 0x0050febeu;
  x *= uint32_t(seed >> 32) | 1u;
  x += uint32_t(seed >> 16);
  x ^= x * 0x878975d6u;
  x *= uint32_t(seed >> 8) | 1u;
  x ^= x * 0x5a71c658u;
  return x;
}

// Owen scramble of a point index: the high bits of the result depend only on
// the high bits of `index`, so every aligned block of 2^m indices maps onto an
// aligned block of 2^m (in a random order). `index_digits` = reverse_bits(index).
constexpr uint32_t shuffle_index(uint32_t index_digits, uint64_t seed) {
  return reverse_bits(owen_permute_digits(index_digits, seed));
}

// Sobol dimension 0 (van der Corput) of point `index`, in digit order, is
// `index` itself. Dimension 1's generator matrix is Pascal's triangle mod 2:
// digit t is the xor of the index bits k with t a bit subset of k (Lucas), a
// superset sum over 5-bit positions done in five butterfly steps. The two
// together are a (0,2)-sequence: every aligned block of 2^m points is a
// (0,m,2)-net.
constexpr uint32_t sobol1_digits(uint32_t index) {
  index ^= (index >> 1) & 0x55555555u;
  index ^= (index >> 2) & 0x33333333u;
  index ^= (index >> 4) & 0x0f0f0f0fu;
  index ^= (index >> 8) & 0x00ff00ffu;
  index ^= (index >> 16) & 0x0000ffffu;
  return index;
}

// Digits (bit 0 first) -> float in [0, 1): the first 24 digits, never 1.0f.
constexpr float digits_to_unit_float(uint32_t digits) {
  return float(reverse_bits(digits) >> 8) * 0x1p-24f;
}

}  // namespace vesper
