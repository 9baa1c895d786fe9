#pragma once
// A job's sampling budget beyond its spp: a noise target (adaptive sampling),
// the minimum spp that goes with it, and a time limit, as `vesper render`
// takes them (--noise-target, --min-spp, --time-limit). A job's spp is the
// most samples a pixel of a frame may take (the renderer's max_spp).
//
// A frame split into sample-range tasks is rendered by independent
// adaptive renders of [begin, end), one per task, whose per-pixel sums and
// counts `vesper merge` adds. task_budget() gives each task its share so that
// the merged frame meets the frame's budget (docs/farm.md, "Noise targets and
// time limits").
#include <optional>
#include <string>

namespace vesper {

// The renderer's default min_spp with a noise target: min(16, max_spp).
inline constexpr int kDefaultMinSpp = 16;

struct RenderBudget {
  // Relative error of each pixel's mean to stop at (> 0); unset: every pixel
  // takes the full spp.
  std::optional<double> noise_target;
  // Samples every pixel takes before it may stop (>= 1, <= spp); only with a
  // noise target. Unset: min(kDefaultMinSpp, spp).
  std::optional<int> min_spp;
  // Seconds of rendering a frame may take (> 0); unset: no limit.
  std::optional<double> time_limit;

  bool operator==(const RenderBudget&) const = default;
  bool empty() const { return !noise_target && !min_spp && !time_limit; }
};

// Why `budget` is not acceptable for frames of `spp` samples: the field at
// fault ("noise_target", "min_spp" or "time_limit", the JSON key; the CLI
// names its flag) and what was expected. nullopt when it is acceptable:
// noise_target and time_limit positive and finite, min_spp only with a
// noise target and in [1, spp].
struct BudgetProblem {
  const char* field;
  std::string message;
};
std::optional<BudgetProblem> budget_problem(const RenderBudget& budget, int spp);

// A budget as asked for (`vesper render`'s flags, a submit's keys): with a
// noise target, max_spp (when given) is the frame's spp instead of spp.
struct BudgetRequest {
  RenderBudget budget;
  std::optional<int> max_spp;
  int frame_spp(int spp) const { return max_spp.value_or(spp); }
  bool operator==(const BudgetRequest&) const = default;
};
// As above for the request's frame spp; also "max_spp" without a noise target.
std::optional<BudgetProblem> budget_problem(const BudgetRequest& request, int spp);

// The shortest decimal text that reads back as the same double: how a
// budget's numbers are written into result-reuse keys and render command
// lines, so equal text means equal values.
std::string exact_text(double v);

// The budget of the task rendering samples [sample_begin, sample_end) of a
// frame of `frame_spp` samples under `frame`. With share f = (end - begin) /
// frame_spp (1/J for J equal tasks):
//   noise_target / sqrt(f)   (X * sqrt(J)): the merged mean averages J
//                            independent estimates, so its variance is 1/J of
//                            each task's; each task also stops at its share
//                            f of the samples the whole frame would take.
//   min(min_spp, end - begin): each task's own variance estimate rests on as
//                            many samples as an unsplit render's (so a split
//                            frame takes at least J * min_spp samples a pixel).
//   time_limit * f:          the frame's seconds are shared, so a frame costs
//                            the same render time however it is split; a split
//                            buys wall-clock time, not extra samples.
// A task that is the whole frame gets the frame's budget, min_spp made
// explicit. Requires 0 <= sample_begin < sample_end <= frame_spp.
RenderBudget task_budget(const RenderBudget& frame, int frame_spp, int sample_begin,
                         int sample_end);

}  // namespace vesper
