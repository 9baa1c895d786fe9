#include "renderer/render/light_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "renderer/integrator/light_tracer.h"
#include "renderer/integrator/light_tracer_splat.h"
#include "renderer/integrator/light_vertex.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper {
namespace {

// Light subpaths traced together by one task (they share a splat buffer).
constexpr uint64_t kSubpathsPerTask = 1024;

}  // namespace

LightSplats::LightSplats(const Scene& scene, const PathTracerOptions& pt,
                         const ChannelLayout& layout, const SamplingPlan& plan, int threads,
                         const std::function<void(uint64_t)>& progress)
    : pixels_(size_t(scene.film.width) * size_t(scene.film.height)) {
  const int groups = int(scene.group_names.size());
  outputs_of_bin_.resize(size_t(kFirstEventKinds * 2 * groups));
  // The bins splats land in: indirect, first event in a medium or on a
  // diffuse surface, a traced light's group. Outputs without any of them
  // (direct light, specular AOVs, layers of other lights) get no sums.
  std::vector<bool> splat_bin(outputs_of_bin_.size(), false);
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (light_is_traced(scene, i))
      for (FirstEvent kind : {FirstEvent::Volume, FirstEvent::Diffuse})
        splat_bin[PathRecord::bin(kind, true, scene.light_group[i], groups)] = true;
  outputs_.push_back(0);
  for (size_t b = 0; b < outputs_of_bin_.size(); ++b) outputs_of_bin_[b].push_back(0);
  for (const BinOutput& o : layout.bin_outputs) {
    if (std::none_of(o.bins.begin(), o.bins.end(), [&](size_t b) { return splat_bin[b]; }))
      continue;
    outputs_.push_back(o.channel);
    for (size_t b : o.bins) outputs_of_bin_[b].push_back(outputs_.size() - 1);
  }
  // Streamed channels the splats reach get a stream-sum column each.
  column_of_slot_.assign(outputs_.size() * 3, -1);
  for (size_t j = 0; j < layout.streamed.size(); ++j)
    for (size_t k = 0; k < outputs_.size(); ++k) {
      const int c = layout.streamed[j] - outputs_[k];
      if (c < 0 || c > 2) continue;
      column_of_slot_[k * 3 + size_t(c)] = int(streamed_of_column_.size());
      streamed_of_column_.push_back(j);
    }
  streamed_ = layout.streamed.size();
  sums_ = std::vector<AtomicExactSum>(pixels_ * outputs_.size() * 3);
  stream_sums_ =
      std::vector<AtomicExactSum>(pixels_ * size_t(kSampleStreams) * streamed_of_column_.size());

  const uint64_t total = uint64_t(pixels_) * uint64_t(plan.cap);
  std::atomic<uint64_t> rays{0}, nonfinite{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<uint64_t>(0, (total + kSubpathsPerTask - 1) / kSubpathsPerTask, 1),
        [&](const tbb::blocked_range<uint64_t>& r) {
          std::vector<CameraSplat> splats;
          for (uint64_t task = r.begin(); task != r.end(); ++task) {
            uint32_t task_rays = 0;  // at most 1024 subpaths' rays
            uint64_t task_nonfinite = 0;
            const uint64_t end = std::min(total, (task + 1) * kSubpathsPerTask);
            for (uint64_t i = task * kSubpathsPerTask; i < end; ++i) {
              // Subpath k of sample index s: its own sampler stream, apart
              // from every camera sample's (pixel indices below pixels_).
              const uint64_t s = uint64_t(plan.begin) + i / pixels_;
              const uint64_t k = i % pixels_;
              Sampler sampler(plan.seed, pixels_ + k, s);
              splats.clear();
              trace_light_path(scene, pt, sampler, task_rays, splats);
              for (const CameraSplat& sp : splats) {
                if (!sp.value.is_finite()) {
                  ++task_nonfinite;
                  continue;
                }
                const size_t bin =
                    PathRecord::bin(sp.kind, true, scene.light_group[sp.light], groups);
                filter_splat(scene.film.filter, scene.film.width, scene.film.height, sp.fx, sp.fy,
                             [&](int x, int y, float w) {
                               add(size_t(y) * size_t(scene.film.width) + size_t(x),
                                   sample_stream(s), bin, sp.value * w);
                             });
              }
            }
            rays += task_rays;
            nonfinite += task_nonfinite;
            progress(end - task * kSubpathsPerTask);
          }
        });
  });
  rays_ = rays;
  nonfinite_ = nonfinite;
}

void LightSplats::add(size_t pixel, int stream, size_t bin, const Rgb& value) {
  // Each sample index's subpaths, one per pixel, estimate every pixel
  // together: a sample's share is the splat over the pixel count, turned
  // into fixed point as a camera sample is.
  ExactSum fixed[3];
  const float per_pixel = 1.f / float(pixels_);
  for (int c = 0; c < 3; ++c) fixed[c] = to_fixed(value[c] * per_pixel);
  const size_t columns = streamed_of_column_.size();
  for (size_t o : outputs_of_bin_[bin])
    for (size_t c = 0; c < 3; ++c) {
      const size_t slot = o * 3 + c;
      sums_[pixel * outputs_.size() * 3 + slot].add(fixed[c]);
      if (const int col = column_of_slot_[slot]; col >= 0)
        stream_sums_[(pixel * size_t(kSampleStreams) + size_t(stream)) * columns + size_t(col)].add(
            fixed[c]);
    }
}

void LightSplats::add_to(size_t p, PixelSums px) const {
  for (size_t o = 0; o < outputs_.size(); ++o)
    for (int c = 0; c < 3; ++c)
      px.sums[size_t(outputs_[o] + c)] += sums_[(p * outputs_.size() + o) * 3 + size_t(c)].load();
  if (!px.stream_sums) return;
  const size_t columns = streamed_of_column_.size();
  for (size_t s = 0; s < size_t(kSampleStreams); ++s)
    for (size_t k = 0; k < columns; ++k)
      px.stream_sums[s * streamed_ + streamed_of_column_[k]] +=
          stream_sums_[(p * size_t(kSampleStreams) + s) * columns + k].load();
}

}  // namespace vesper
