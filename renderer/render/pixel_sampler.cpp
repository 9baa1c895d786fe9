#include "renderer/render/pixel_sampler.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/sampling/pixel_filter.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper {
namespace {

// One camera sample's value of every channel in fixed point, into v (0
// where the sample contributes nothing). A non-finite radiance would poison
// the whole pixel: it is dropped (its radiance and layers stay 0), and false
// returned so that it is counted.
bool sample_values(const PathResult& r, const PathRecord& record, const ChannelLayout& layout,
                   std::vector<ExactSum>& v) {
  std::fill(v.begin(), v.end(), ExactSum(0));
  const bool finite = r.radiance.is_finite();
  if (finite) {
    for (int c = 0; c < 3; ++c) v[size_t(c)] = to_fixed(r.radiance[c]);
    for (const BinOutput& o : layout.bin_outputs) {
      Rgb sum;
      for (size_t b : o.bins) sum += record.bins()[b];
      for (int c = 0; c < 3; ++c) v[size_t(o.channel + c)] = to_fixed(sum[c]);
    }
  }
  v[3] = to_fixed(r.alpha);
  for (const BinOutput& o : layout.bin_outputs)
    if (o.alpha_channel >= 0 && std::isfinite(r.camera_transmittance))
      v[size_t(o.alpha_channel)] = to_fixed(float(1.0 - r.camera_transmittance));
  if (layout.albedo >= 0 && r.albedo.is_finite())
    for (int c = 0; c < 3; ++c) v[size_t(layout.albedo + c)] = to_fixed(r.albedo[c]);
  if (layout.normal >= 0 && is_finite(r.normal))
    for (int c = 0; c < 3; ++c) v[size_t(layout.normal + c)] = to_fixed(r.normal[c]);
  if (layout.depth >= 0 && std::isfinite(r.depth)) v[size_t(layout.depth)] = to_fixed(r.depth);
  return finite;
}

// The camera ray through raster point (fx, fy); with motion blur at the
// sample's own time in the shutter, from the camera at that time.
Ray camera_ray(const Scene& scene, const Sampler& sampler, float fx, float fy, Vec2 u_lens) {
  if (!scene.motion_blur) return scene.camera.generate_ray(fx, fy, u_lens);
  const float time = sampler.shutter_time();
  Ray ray = scene.camera_steps.empty()
                ? scene.camera.generate_ray(fx, fy, u_lens)
                : camera_at(scene.camera_steps, time).generate_ray(fx, fy, u_lens);
  ray.time = time;
  return ray;
}

}  // namespace

SampleCounts sample_pixel(const PixelSamplerContext& c, int x, int y, int64_t first, int64_t last,
                          const PathTracerOptions& pt, const PathRecord& record, PixelSums px) {
  SampleCounts counts;
  const std::vector<int>& streamed = c.layout.streamed;
  std::vector<ExactSum> v(c.layout.names.size());
  const uint64_t pixel_index = uint64_t(y) * uint64_t(c.width) + uint64_t(x);
  for (int64_t i = first; i < last; ++i) {
    const uint64_t s = uint64_t(c.range_begin + i);
    Sampler sampler(c.seed, pixel_index, s);
    const Vec2 offset = sample_pixel_filter(c.scene.film.filter, sampler.next2());
    const Vec2 u_lens = sampler.next2();
    const Ray ray = camera_ray(c.scene, sampler, float(x) + 0.5f + offset.x,
                               float(y) + 0.5f + offset.y, u_lens);
    const PathResult r = trace_path(c.scene, ray, sampler, pt);
    counts.rays += r.rays;
    if (c.crypto) c.crypto->add(pixel_index, r.first_shape);
    if (!sample_values(r, record, c.layout, v)) ++counts.nonfinite;
    for (size_t k = 0; k < v.size(); ++k) px.sums[k] += v[k];
    const size_t stream = size_t(sample_stream(s));
    ++px.counts[stream];
    if (px.stream_sums)
      for (size_t j = 0; j < streamed.size(); ++j)
        px.stream_sums[stream * streamed.size() + j] += v[size_t(streamed[j])];
  }
  counts.camera_samples = uint64_t(last > first ? last - first : 0);
  return counts;
}

}  // namespace vesper
