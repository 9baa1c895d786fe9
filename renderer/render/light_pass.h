#pragma once
// The light tracer's pass (integrator/light_tracer.h) over a render's sample
// range, traced before the camera pass: for each sample index one light
// subpath per pixel, their camera connections summed per pixel into the
// beauty and the layers and transport AOVs their paths belong to. The
// camera pass adds each pixel's splat sums to its own sample sums
// (add_to), so the pixel is the mean of (camera sample + the splats of that
// sample index's subpaths), and sample ranges still merge exactly. Internal
// to render/.
#include <cstdint>
#include <functional>
#include <vector>

#include "renderer/integrator/path_tracer.h"
#include "renderer/output/atomic_exact_sum.h"
#include "renderer/output/film_sums.h"
#include "renderer/render/channel_layout.h"
#include "renderer/render/sampling_plan.h"

namespace vesper {

class LightSplats {
 public:
  // Traces plan.cap * width * height light subpaths on `threads` threads;
  // `progress(n)` is called (from worker threads) as each n more are done.
  LightSplats(const Scene& scene, const PathTracerOptions& pt, const ChannelLayout& layout,
              const SamplingPlan& plan, int threads, const std::function<void(uint64_t)>& progress);

  // Adds pixel p's splat sums to its sums (and stream sums when px has them).
  void add_to(size_t p, PixelSums px) const;

  uint64_t rays() const { return rays_; }
  uint64_t nonfinite() const { return nonfinite_; }  // splats dropped as NaN or Inf

 private:
  void add(size_t pixel, int stream, size_t bin, const Rgb& value);

  size_t pixels_ = 0, streamed_ = 0;  // streamed_: layout.streamed.size()
  // Each output RGB the splats reach: its first channel; the beauty first.
  // Its channels are slots 3 k, 3 k + 1, 3 k + 2.
  std::vector<int> outputs_;
  std::vector<std::vector<size_t>> outputs_of_bin_;  // path-record bin -> outputs_ indices
  std::vector<int> column_of_slot_;                  // slot -> its stream-sum column, or -1
  std::vector<size_t> streamed_of_column_;           // column -> its index in layout.streamed
  // Exact sums that the threads add to (any thread count gives the same
  // bits): [pixel][slot] and [pixel][stream][column]. 24 bytes
  // each: 72 per pixel for the beauty, as much for each indirect AOV or
  // layer splats reach, 4 times that for each such channel streamed.
  std::vector<AtomicExactSum> sums_, stream_sums_;
  uint64_t rays_ = 0, nonfinite_ = 0;
};

}  // namespace vesper
