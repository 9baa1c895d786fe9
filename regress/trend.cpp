#include "regress/trend.h"

#include <algorithm>

namespace vesper::regress {

TrendPoint trend_point(const SceneResult& scene, const std::string& started_at) {
  TrendPoint p;
  p.scene = scene.name;
  p.started_at = started_at;
  p.verdict = scene.verdict;
  p.reused = scene.reused;
  p.render_seconds = scene.reused ? 0 : scene.new_seconds;
  for (const LayerResult& layer : scene.layers) {
    p.max_abs_z = std::max(p.max_abs_z, layer.max_abs_z);
    p.histogram_distance = std::max(p.histogram_distance, layer.histogram_distance);
    if (layer.has_variance)
      p.min_detectable_change = std::max(p.min_detectable_change, layer.min_detectable_change);
  }
  return p;
}

std::vector<TrendPoint> trend_points(const RunResult& run) {
  std::vector<TrendPoint> points;
  points.reserve(run.scenes.size());
  for (const SceneResult& scene : run.scenes) points.push_back(trend_point(scene, run.started_at));
  return points;
}

}  // namespace vesper::regress
