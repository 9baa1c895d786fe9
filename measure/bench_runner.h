#pragma once
// The benchmark loop: for each scene of the set and each renderer, the
// reference (cached or rendered as two halves), then the spp ladder, each
// rung scored against that renderer's own reference; then times to the
// targets and, for peers, the comparison with Vesper (renderers[0]).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "common/json_error.h"
#include "measure/bench_renderer.h"
#include "measure/bench_result.h"
#include "measure/bench_set.h"

namespace vesper::measure {

struct RunnerOptions {
  std::filesystem::path refs_dir;  // the reference cache
  bool quick = false;              // each scene's `quick` settings
  int threads = 0;                 // 0 = all cores
  // Seed of the measured renders. The reference halves use seeds derived from
  // it (reference_seeds), never equal to it: a reference sharing samples with
  // a measurement would make that measurement look better than it is.
  uint64_t seed = 1;
  std::vector<double> targets = {1e-2, 4e-3};
};

// The seeds of reference halves A and B for measurement seed `seed`.
std::pair<uint64_t, uint64_t> reference_seeds(uint64_t seed);

// What the runner tells whoever watches (the CLI's progress bar and log).
struct RunnerEvents {
  // A render starts: "scene 3/6 fog-shafts: vesper reference 2048 spp (half 1/2)".
  std::function<void(const std::string& label)> render_begins;
  std::function<void()> render_ends;
  std::function<void(const std::string& message)> warn;
  std::function<void(const std::string& message)> info;
};

// A scene that cannot be measured at all (it does not load): bad input, like
// a bad set file; what() names the scene file and the problem.
class BenchSceneError : public JsonError {
 public:
  using JsonError::JsonError;
};

// Checks every scene before anything renders: a scene whose referenced file
// is absent is marked skipped with a note; one that fails to load throws
// BenchSceneError. Fills name, kind, sizes, ladder and scene hash.
std::vector<SceneResult> prepare_scenes(const BenchSet& set, bool quick);

// Runs everything. A renderer that throws leaves its error in its RendererRun
// and the run goes on with the next renderer or scene.
BenchReport run_bench(const BenchSet& set, const std::vector<BenchRenderer>& renderers,
                      const RunnerOptions& options, const RunnerEvents& events = {});

}  // namespace vesper::measure
