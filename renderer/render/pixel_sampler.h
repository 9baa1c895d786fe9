#pragma once
// Takes a pixel's samples [first, last) of the range and adds them to its
// exact sums. Internal to render/.
#include <cstdint>

#include "renderer/integrator/path_tracer.h"
#include "renderer/output/film_sums.h"
#include "renderer/render/channel_layout.h"
#include "renderer/render/cryptomatte.h"

namespace vesper {

// What every pixel of one render shares.
struct PixelSamplerContext {
  const Scene& scene;
  const ChannelLayout& layout;
  uint64_t seed = 0;
  int range_begin = 0;  // sample index of the range's first sample
  int width = 0;
  CryptoCounts* crypto = nullptr;  // counts each sample's first hit when set
};

struct SampleCounts {
  uint64_t camera_samples = 0, rays = 0, nonfinite = 0;
  SampleCounts& operator+=(const SampleCounts& o) {
    camera_samples += o.camera_samples;
    rays += o.rays;
    nonfinite += o.nonfinite;
    return *this;
  }
};

// Samples [range_begin + first, range_begin + last) of pixel (x, y) into px
// (its stream counts and, when px.stream_sums is set, the stream sums too).
// `pt.record` must be set when the layout has path-record outputs.
SampleCounts sample_pixel(const PixelSamplerContext& c, int x, int y, int64_t first, int64_t last,
                          const PathTracerOptions& pt, const PathRecord& record, PixelSums px);

}  // namespace vesper
