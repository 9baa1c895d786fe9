#pragma once
// The renders of `vesper regress --local`: each suite scene and frame through
// a `vesper render`-compatible program (this binary, or --renderer for a
// wrapper), timed by wall clock and repeated for the timing; and the goldens
// those renders (or the farm's, regress_farm.h) become with --update-goldens.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "jobs/render_overrides.h"
#include "regress/suite.h"

namespace vesper::cli {

// Every (scene, frame) of the suite, with the label its files get: the
// scene's name, with ".<frame>" when it has several frames.
struct SuiteFrame {
  const regress::SuiteScene* scene;
  int frame;
  std::string label;
};
std::vector<SuiteFrame> suite_frames(const regress::Suite& suite);

// An EXR's own render time (its vesper:render_seconds: rendering only, no
// process start, scene load or writing); nullopt when it does not say or
// cannot be read.
std::optional<double> exr_render_seconds(const std::filesystem::path& exr);

struct SuiteRender {
  std::string label;  // the SuiteFrame's
  std::filesystem::path exr;
  // Local: wall time of each repeat. Farm: the render's own time (its EXR's
  // vesper:render_seconds), once; none when the output does not say.
  std::vector<double> seconds;
  std::string error;     // non-empty: the render failed (and why)
  bool on_farm = false;  // rendered by `vesper regress --server`
  bool reused = false;   // on the farm: every task took an identical earlier result
};

struct RegressRenderSettings {
  std::filesystem::path renderer;
  std::filesystem::path out_dir;
  std::optional<unsigned long long> seed;
  std::optional<int> threads;
  int repeats = 1;
};

// What every render of `scene` asks beyond the scene, locally as `vesper
// render` flags and on the farm as its job's render overrides, so that both
// render the same: the variance of the beauty and of every layer (the
// comparison's noise model), the suite's film scale and --seed.
RenderOverrides suite_render_overrides(const regress::SuiteScene& scene,
                                       std::optional<unsigned long long> seed);

// Renders `scene` at `frame` (`label` names the output file) with
// suite_render_overrides.
SuiteRender render_suite_frame(const regress::SuiteScene& scene, int frame,
                               const std::string& label, const RegressRenderSettings& settings);

// The golden of `label` in `dir`: its EXR and its sidecar JSON (renderer
// version, scene hash, spp, render times, the beauty's histogram).
std::filesystem::path golden_image(const std::filesystem::path& dir, const std::string& label);
std::filesystem::path golden_sidecar(const std::filesystem::path& dir, const std::string& label);

// Moves the render into `dir` as the golden and writes its sidecar, each by
// rename. Throws std::runtime_error naming the file on failure.
void write_golden(const SuiteRender& render, const std::filesystem::path& dir);

// The golden's render time from its sidecar ("seconds": the fastest of its
// repeats, or the farm's render time with "timing": "farm"); nullopt if it
// has none.
struct GoldenTime {
  double seconds = 0;
  bool on_farm = false;  // a farm render's own time, not a local wall time
};
std::optional<GoldenTime> golden_seconds(const std::filesystem::path& dir,
                                         const std::string& label);

}  // namespace vesper::cli
