#pragma once
// What one `vesper bench` run measured: per scene and renderer, the
// reference (cache hit or not, its noise floor) and the curve of relMSE
// against time; the times to reach each target; with peers, the equal-error
// time ratios, the project's goals and how well the two references agree.
// Everything the report files (bench_report.h) and the plot are made of.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "measure/reference_agreement.h"
#include "measure/time_to_error.h"

namespace vesper::measure {

struct Measurement {
  int spp = 0;
  double render_seconds = 0, wall_seconds = 0;
  double relmse = 0;  // against this renderer's own reference
};

struct TargetTime {
  double target = 0;  // relMSE
  TimeToError time;
};

struct RendererRun {
  std::string renderer;
  std::string cache_key;  // BenchRenderer::cache_key: which build measured
  std::string reference_file;
  bool reference_cached = false;
  double reference_seconds = 0;  // render time of both halves (when it was rendered)
  double noise_floor = 0;
  std::vector<Measurement> curve;
  std::vector<TargetTime> times;  // one per target
  std::string error;              // the renderer failed: what it said (curve may be partial)
};

// Vesper's time over the peer's, at equal error.
struct RatioAtTarget {
  double target = 0;
  std::optional<double> ratio;  // none when either time is unknown
  bool approximate = false;     // either time extrapolated or an upper bound
  double goal = 0;              // the project's goal for the scene's kind
  std::optional<bool> goal_met;
};

struct PeerComparison {
  std::string peer;
  std::optional<ReferenceAgreement> agreement;  // none when either reference is missing
  std::vector<RatioAtTarget> ratios;
};

struct SceneResult {
  std::string name, kind, scene_path, scene_hash;
  int width = 0, height = 0, reference_spp = 0;
  std::vector<int> spp_ladder;
  bool skipped = false;
  std::string note;                         // why skipped
  std::vector<RendererRun> runs;            // one per renderer, vesper first
  std::vector<PeerComparison> comparisons;  // one per peer
};

struct BenchReport {
  std::string set_path;
  bool quick = false;
  int threads = 0;
  uint64_t seed = 0;
  std::vector<double> targets;
  std::vector<std::string> renderers;
  std::vector<SceneResult> scenes;
  double total_seconds = 0;
  bool any_error() const {
    for (const SceneResult& s : scenes)
      for (const RendererRun& r : s.runs)
        if (!r.error.empty()) return true;
    return false;
  }
};

// The project's goal (issue 14): Vesper's equal-error time at most 0.8x
// Cycles' on surface scenes and 0.5x on volume scenes.
inline double goal_ratio(const std::string& kind) { return kind == "volume" ? 0.5 : 0.8; }

// A measured relMSE is the render's error plus the reference's own (its
// noise floor): once the floor is half the target or more, the time to that
// target says more about the reference than about the renderer.
inline bool reference_limited(double noise_floor, double target) {
  return noise_floor >= 0.5 * target;
}

}  // namespace vesper::measure
