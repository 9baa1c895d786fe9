#pragma once
// Counter-based low-discrepancy samples: every value is a pure function of
// (seed, pixel, sample index, dimension). This is what makes an image bitwise
// identical for any thread count and lets sample ranges be rendered apart.
//
// Sample s of a pixel is point stream_point(s) of stream sample_stream(s)
// (sample_streams.h). Each (seed, pixel, stream) has its own independent
// random scrambles, so the streams' means are independent estimates of the
// pixel. Each next1()/next2() call is one dimension slot; a slot is the first
// one or two Sobol dimensions of the stream's point index, with the index
// shuffled and the coordinates Owen-scrambled by seeds of that slot
// (owen_scrambled_sobol.h). Hence within a stream:
// - each slot pair is a progressive (0,2)-sequence: the first 2^m points
//   (any m: the final count may be unknown) form a (0,m,2)-net;
// - different slots are decorrelated by their independent index shuffles;
// - every point is uniform on [0,1)^slots, whatever the integrator does with
//   the slots, so estimates stay unbiased.
#include <cstdint>

#include "renderer/math/vec.h"
#include "renderer/sampling/owen_scrambled_sobol.h"
#include "renderer/sampling/random_hash.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper {

class Sampler {
 public:
  Sampler(uint64_t seed, uint64_t pixel_index, uint64_t sample_index)
      : key_(hash_combine(hash_combine(mix64(seed), pixel_index),
                          uint64_t(sample_stream(sample_index)))),
        // A stream holds up to 2^32 points; beyond that its sequence repeats.
        index_digits_(reverse_bits(uint32_t(stream_point(sample_index)))) {}
  // A single random point: its slots are independent uniform numbers (for
  // tests and tools that want plain random numbers).
  explicit Sampler(uint64_t key) : key_(mix64(key)), index_digits_(0) {}

  float next1() {
    const uint32_t index = shuffle_index(index_digits_, slot_seed(0));
    const float u = digits_to_unit_float(owen_permute_digits(index, slot_seed(1)));
    ++slot_;
    return u;
  }
  Vec2 next2() {
    const uint32_t index = shuffle_index(index_digits_, slot_seed(0));
    const Vec2 u{digits_to_unit_float(owen_permute_digits(index, slot_seed(1))),
                 digits_to_unit_float(owen_permute_digits(sobol1_digits(index), slot_seed(2)))};
    ++slot_;
    return u;
  }
  // Slots used so far (one per next1 or next2 call).
  uint32_t dimension() const { return slot_; }

 private:
  // Three independent seeds per slot: the index shuffle and one per coordinate.
  uint64_t slot_seed(uint32_t lane) const {
    return mix64(key_ + 0x9e3779b97f4a7c15ULL * (3 * uint64_t(slot_) + lane + 1));
  }

  uint64_t key_;           // the stream: hash of (seed, pixel, stream)
  uint32_t index_digits_;  // the point index within the stream, bit-reversed
  uint32_t slot_ = 0;
};

}  // namespace vesper
