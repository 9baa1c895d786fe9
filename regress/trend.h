#pragma once
// One scene's figures in one run, as the history database keeps them and the
// report plots them across runs (time, noise, error). A plain struct so the
// history (which stores and loads them) and the report (which draws them)
// meet here and nowhere else.
#include <string>
#include <vector>

#include "regress/regress_result.h"

namespace vesper::regress {

struct TrendPoint {
  std::string scene;
  std::string started_at;  // the run's, ISO 8601 UTC: orders the points
  Verdict verdict = Verdict::Pass;
  double render_seconds = 0;  // the new render's time (median of repeats); 0 = reused/unknown
  bool reused = false;        // the farm reused an identical task: no render, no timing
  double max_abs_z = 0;       // the worst layer's
  // The weakest guarantee over the layers with a noise model: the smallest
  // relative change every one of them would have flagged. 0 = none tested.
  double min_detectable_change = 0;
  double histogram_distance = 0;  // the largest over the layers (stops)
};

// One scene's point in the run started at `started_at`.
TrendPoint trend_point(const SceneResult& scene, const std::string& started_at);
// The run's own points, one per scene, in the run's scene order.
std::vector<TrendPoint> trend_points(const RunResult& run);

}  // namespace vesper::regress
