#pragma once
// A pixel's samples are dealt round-robin to kSampleStreams independently
// scrambled low-discrepancy streams: sample s is point s / K of stream s % K.
// Within a stream the points are stratified (correlated), so the plain sample
// variance would overstate the noise; the streams' means, however, are
// independent estimates of the pixel, and their spread gives an unbiased
// variance of the pixel mean (output/film_sums.h).
#include <cstdint>

namespace vesper {

inline constexpr int kSampleStreams = 4;

constexpr int sample_stream(uint64_t sample_index) {
  return int(sample_index % uint64_t(kSampleStreams));
}
constexpr uint64_t stream_point(uint64_t sample_index) {
  return sample_index / uint64_t(kSampleStreams);
}

}  // namespace vesper
