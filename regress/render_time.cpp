#include "regress/render_time.h"

#include <algorithm>

#include <fmt/format.h>

#include "regress/median.h"
#include "regress/verdicts.h"

namespace vesper::regress {

void judge_render_time(SceneResult& scene, const Thresholds& thresholds,
                       std::optional<double> history_seconds) {
  std::vector<double> t = scene.new_seconds_repeats;
  if (t.empty() && scene.new_seconds > 0) t.push_back(scene.new_seconds);
  if (scene.reused || t.empty() || !(scene.golden_seconds > 0)) return;
  scene.new_seconds = median(t);
  const double fastest = *std::min_element(t.begin(), t.end());
  const double vs_golden = fastest / scene.golden_seconds;
  const bool vs_history = !history_seconds || !(*history_seconds > 0) ||
                          fastest / *history_seconds > thresholds.max_slowdown;
  if (vs_golden <= thresholds.max_slowdown || !vs_history) return;
  scene.verdict = worse(scene.verdict, Verdict::Regressed);
  std::string reason = fmt::format(
      "render time {:.2f} s (fastest of {}) is {:.2f}x the golden's {:.2f} s (limit max_slowdown "
      "{:g})",
      fastest, t.size(), vs_golden, scene.golden_seconds, thresholds.max_slowdown);
  if (history_seconds && *history_seconds > 0)
    reason += fmt::format(" and {:.2f}x the recent median {:.2f} s", fastest / *history_seconds,
                          *history_seconds);
  scene.reasons.push_back(reason);
}

}  // namespace vesper::regress
