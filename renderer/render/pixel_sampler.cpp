#include "renderer/render/pixel_sampler.h"

#include <cmath>

#include "renderer/sampling/pixel_filter.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper {
namespace {

// Adds one camera sample's values to the pixel's sums. A non-finite radiance
// would poison the whole pixel: it is dropped, and false returned so that it is counted.
bool accumulate(PixelSums px, int stream, const PathResult& r, const PathRecord& record,
                const ChannelLayout& layout) {
  ExactSum* acc = px.sums;
  const bool finite = r.radiance.is_finite();
  if (finite) {
    const ExactSum rgb[3] = {to_fixed(r.radiance.r), to_fixed(r.radiance.g),
                             to_fixed(r.radiance.b)};
    for (int c = 0; c < 3; ++c) acc[c] += rgb[c];
    if (px.stream_sums)
      for (int c = 0; c < 3; ++c) px.stream_sums[stream * 3 + c] += rgb[c];
    for (const BinOutput& o : layout.bin_outputs) {
      Rgb sum;
      for (size_t b : o.bins) sum += record.bins()[b];
      for (int c = 0; c < 3; ++c) acc[size_t(o.channel + c)] += to_fixed(sum[c]);
    }
  }
  acc[3] += to_fixed(r.alpha);
  for (const BinOutput& o : layout.bin_outputs)
    if (o.alpha_channel >= 0 && std::isfinite(r.camera_transmittance))
      acc[size_t(o.alpha_channel)] += to_fixed(float(1.0 - r.camera_transmittance));
  if (layout.albedo >= 0 && r.albedo.is_finite())
    for (int c = 0; c < 3; ++c) acc[size_t(layout.albedo + c)] += to_fixed(r.albedo[c]);
  if (layout.normal >= 0 && is_finite(r.normal))
    for (int c = 0; c < 3; ++c) acc[size_t(layout.normal + c)] += to_fixed(r.normal[c]);
  if (layout.depth >= 0 && std::isfinite(r.depth)) acc[size_t(layout.depth)] += to_fixed(r.depth);
  return finite;
}

}  // namespace

SampleCounts sample_pixel(const PixelSamplerContext& c, int x, int y, int64_t first, int64_t last,
                          const PathTracerOptions& pt, const PathRecord& record, PixelSums px) {
  SampleCounts counts;
  const uint64_t pixel_index = uint64_t(y) * uint64_t(c.width) + uint64_t(x);
  for (int64_t i = first; i < last; ++i) {
    const uint64_t s = uint64_t(c.range_begin + i);
    Sampler sampler(c.seed, pixel_index, s);
    const Vec2 offset = sample_pixel_filter(c.scene.film.filter, sampler.next2());
    const Vec2 u_lens = sampler.next2();
    const Ray ray =
        c.scene.camera.generate_ray(float(x) + 0.5f + offset.x, float(y) + 0.5f + offset.y, u_lens);
    const PathResult r = trace_path(c.scene, ray, sampler, pt);
    counts.rays += r.rays;
    const int stream = sample_stream(s);
    ++px.counts[stream];
    if (!accumulate(px, stream, r, record, c.layout)) ++counts.nonfinite;
  }
  counts.camera_samples = uint64_t(last > first ? last - first : 0);
  return counts;
}

}  // namespace vesper
