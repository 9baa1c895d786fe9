#pragma once
// 64-bit hashing for counter-based random numbers: seeds, keys and the
// per-dimension scramble seeds of the Sampler are all hashes of integers.
#include <cstdint>

namespace vesper {

// SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr uint64_t hash_combine(uint64_t a, uint64_t b) {
  return mix64(a ^ (b + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2)));
}

// The seed of frame `frame` of an animation: frames get independent noise
// (like Cycles' animated seed) while each stays reproducible.
constexpr uint64_t frame_seed(uint64_t seed, int64_t frame) {
  return hash_combine(seed, uint64_t(frame) ^ 0x6672616d65ULL);
}

}  // namespace vesper
