#include "jobs/render_budget.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesper {

RenderBudget task_budget(const RenderBudget& frame, int frame_spp, int sample_begin,
                         int sample_end) {
  if (sample_begin < 0 || sample_begin >= sample_end || sample_end > frame_spp)
    throw std::invalid_argument("task_budget: samples [" + std::to_string(sample_begin) + ", " +
                                std::to_string(sample_end) + ") are not a range of a " +
                                std::to_string(frame_spp) + "-spp frame");
  const int samples = sample_end - sample_begin;
  const double share = double(samples) / double(frame_spp);
  RenderBudget task;
  if (frame.noise_target) {
    task.noise_target = *frame.noise_target / std::sqrt(share);
    const int min_spp = frame.min_spp.value_or(std::min(kDefaultMinSpp, frame_spp));
    task.min_spp = std::min(min_spp, samples);
  }
  if (frame.time_limit) task.time_limit = *frame.time_limit * share;
  return task;
}

}  // namespace vesper
