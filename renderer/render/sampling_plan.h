#pragma once
// How many samples each pixel takes, and when: one pass of the whole range,
// or (with a noise target or a time limit) passes that each add samples to
// the pixels still above the target, until they converge, reach the range's
// end, or the time is up. Internal to render/.
#include <cstdint>
#include <optional>
#include <vector>

#include "renderer/output/film_sums.h"
#include "renderer/render/render.h"

namespace vesper {

struct SamplingPlan {
  int begin = 0, end = 0;  // the sample index range
  int cap = 0;             // end - begin: most samples a pixel may take
  uint64_t seed = 0;
  std::optional<double> noise_target;
  std::optional<double> time_limit;
  int first_pass = 0;  // samples of every pixel in the first pass
  bool multipass() const { return noise_target.has_value() || time_limit.has_value(); }
};

// The plan for `options` over `scene` (options override render.*). Throws
// std::invalid_argument naming the setting (render.min_spp / --min-spp ...).
SamplingPlan plan_sampling(const RenderDesc& render, const RenderOptions& options);

// A pixel's sample count after the next pass, given n now: grows by half
// (at least kSampleStreams), kept a multiple of kSampleStreams, at most cap.
int64_t next_sample_count(int64_t n, int64_t cap);

// Where each pixel stands after a pass. With a target, a pixel's error is the
// larger of its own estimate and the RMS over its 3x3 neighbourhood: pooling
// steadies the estimate (each pixel's has only K - 1 degrees of freedom) and
// the max keeps a lone noisy pixel going. Without one, every pixel below the
// cap is Active.
enum class PixelState : uint8_t { Converged, Active, Capped };
std::vector<PixelState> pixel_states(const FilmSums& film, std::optional<double> target,
                                     int64_t cap);

}  // namespace vesper
