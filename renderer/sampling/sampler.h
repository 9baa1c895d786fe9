#pragma once
// Counter-based random numbers: every value is a pure function of
// (seed, pixel, sample index, dimension). This is what makes an image bitwise
// identical for any thread count and lets sample ranges be rendered apart.
#include <cstdint>

#include "renderer/math/constants.h"
#include "renderer/math/vec.h"

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

// Uniform float in [0, 1) from the top 24 bits.
constexpr float to_unit_float(uint64_t bits) { return float(bits >> 40) * 0x1p-24f; }

class Sampler {
 public:
  Sampler(uint64_t seed, uint64_t pixel_index, uint64_t sample_index)
      : key_(hash_combine(hash_combine(mix64(seed), pixel_index), sample_index)) {}
  explicit Sampler(uint64_t key) : key_(mix64(key)) {}

  float next1() { return to_unit_float(mix64(key_ + 0x9e3779b97f4a7c15ULL * ++dim_)); }
  Vec2 next2() {
    const float a = next1();
    return {a, next1()};
  }
  uint32_t dimension() const { return dim_; }

 private:
  uint64_t key_;
  uint32_t dim_ = 0;
};

}  // namespace vesper
