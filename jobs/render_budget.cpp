#include "jobs/render_budget.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesper {

std::string exact_text(double v) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  return std::string(buf, end);
}

std::optional<BudgetProblem> budget_problem(const RenderBudget& b, int spp) {
  auto positive = [](double v) { return v > 0 && std::isfinite(v); };
  if (b.noise_target && !positive(*b.noise_target))
    return BudgetProblem{"noise_target",
                         "expected a positive number (the relative error of each "
                         "pixel's mean to stop at), got " +
                             std::to_string(*b.noise_target)};
  if (b.min_spp && !b.noise_target)
    return BudgetProblem{"min_spp",
                         "min_spp needs a noise_target (without one every pixel takes "
                         "the full spp)"};
  if (b.min_spp && (*b.min_spp < 1 || *b.min_spp > spp))
    return BudgetProblem{"min_spp", "expected an integer in [1, " + std::to_string(spp) +
                                        "] (at most the frame's spp, or max_spp), got " +
                                        std::to_string(*b.min_spp)};
  if (b.time_limit && !positive(*b.time_limit))
    return BudgetProblem{"time_limit", "expected a positive number of seconds, got " +
                                           std::to_string(*b.time_limit)};
  return std::nullopt;
}

std::optional<BudgetProblem> budget_problem(const BudgetRequest& r, int spp) {
  if (r.max_spp && !r.budget.noise_target)
    return BudgetProblem{"max_spp",
                         "max_spp needs a noise_target (without one every pixel "
                         "takes spp samples)"};
  if (r.max_spp && *r.max_spp < 1)
    return BudgetProblem{"max_spp",
                         "expected a positive integer, got " + std::to_string(*r.max_spp)};
  return budget_problem(r.budget, r.frame_spp(spp));
}

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
