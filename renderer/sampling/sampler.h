#pragma once
// Counter-based low-discrepancy samples: every value is a pure function of
// (seed, pixel, sample index, dimension). This is what makes an image bitwise
// identical for any thread count and lets sample ranges be rendered apart.
//
// Sample s of a pixel is point stream_point(s) of stream sample_stream(s)
// (sample_streams.h). Each (seed, pixel, stream) has its own random seeds, so
// the streams' means are independent estimates of the pixel. Each next1() or
// next2() call is one dimension slot. The first kLowDiscrepancySlots slots
// are the first two Sobol dimensions of the stream's point index, shuffled by
// a hash-based nested (Owen) scramble and digitally shifted by seeds of that
// slot (shuffled_sobol.h). Within a stream:
// - a slot's pair is a progressive (0,2)-sequence: the first 2^m points, for
//   every m (the final count may be unknown), form a (0,m,2)-net; a next1
//   slot takes its first coordinate, stratified in 2^m equal intervals;
// - slots are decorrelated by their independent index shuffles;
// - every point is uniform on [0,1)^slots whatever the integrator does with
//   the slots, so estimates stay unbiased.
// Later slots are independent random numbers: deep path vertices and volume
// tracking loops (many slots) gain little from stratification, and a hash is
// cheaper (bench/README.md, "Sampler").
#include <cstdint>

#include "renderer/math/vec.h"
#include "renderer/sampling/random_hash.h"
#include "renderer/sampling/sample_streams.h"
#include "renderer/sampling/shuffled_sobol.h"

namespace vesper {

class Sampler {
 public:
  static constexpr uint32_t kLowDiscrepancySlots = 16;

  Sampler(uint64_t seed, uint64_t pixel_index, uint64_t sample_index)
      : stream_key_(hash_combine(hash_combine(mix64(seed), pixel_index),
                                 uint64_t(sample_stream(sample_index)))),
        // A stream's sequence repeats after 2^32 points (2^34 samples a pixel).
        index_bits_(reverse_bits(uint32_t(stream_point(sample_index)))) {}
  // A single random point: its slots are independent uniform numbers (for
  // tests and tools that want plain random numbers).
  explicit Sampler(uint64_t key) : stream_key_(mix64(key)), index_bits_(0) {}

  float next1() {
    if (slot_ >= kLowDiscrepancySlots) return unit_float(random_slot_hash() >> 40);
    const uint64_t h = slot_hash();
    return fraction_to_float(shuffled_sobol0(index_bits_, uint32_t(h)) ^ uint32_t(h >> 32));
  }
  Vec2 next2() {
    if (slot_ >= kLowDiscrepancySlots) {
      const uint64_t h = random_slot_hash();  // 24 bits for each coordinate
      return {unit_float(h >> 40), unit_float((h >> 16) & 0xffffffu)};
    }
    const uint64_t h = slot_hash();
    const uint32_t x = shuffled_sobol0(index_bits_, uint32_t(h));
    const uint32_t shift = uint32_t(h >> 32);  // one random digital shift for both coordinates
    return {fraction_to_float(x ^ shift),
            fraction_to_float(sobol1_from_sobol0(x) ^ (shift << 16 | shift >> 16))};
  }
  // The instant in the shutter, [0, 1), a camera sample lives at (motion
  // blur). A dimension of its own outside the slot sequence: drawing it or
  // not shifts no other dimension, so a still scene's samples, and a
  // zero-length shutter's, are bit for bit those without motion blur. Within
  // a stream it is stratified like a slot (its own shuffle and shift).
  float shutter_time() const {
    const uint64_t h = mix64(stream_key_ ^ 0x5348555454455221ULL);  // "SHUTTER!"
    return fraction_to_float(shuffled_sobol0(index_bits_, uint32_t(h)) ^ uint32_t(h >> 32));
  }
  // Slots used so far (one per next1 or next2 call).
  uint32_t dimension() const { return slot_; }

 private:
  // One 64-bit hash per slot: the shuffle seed (low half) and the shift (high half).
  uint64_t slot_hash() { return mix64(stream_key_ + 0x9e3779b97f4a7c15ULL * ++slot_); }
  // Distinct (point, slot) give distinct hash inputs within a stream.
  uint64_t random_slot_hash() {
    return mix64(stream_key_ ^ uint64_t(index_bits_) << 32 ^ 0x9e3779b97f4a7c15ULL * ++slot_);
  }
  static float unit_float(uint64_t bits24) { return float(bits24) * 0x1p-24f; }

  uint64_t stream_key_;  // hash of (seed, pixel, stream)
  uint32_t index_bits_;  // the point index within the stream, bit-reversed
  uint32_t slot_ = 0;
};

}  // namespace vesper
