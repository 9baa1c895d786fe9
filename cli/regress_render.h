#pragma once
// The renders of `vesper regress --local`: each suite scene and frame through
// a `vesper render`-compatible program (this binary, or --renderer for a
// wrapper), timed by wall clock and repeated for the timing; and the goldens
// those renders become with --update-goldens.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "regress/suite.h"

namespace vesper::cli {

struct SuiteRender {
  std::string label;  // the scene's name, with ".<frame>" when it has several frames
  std::filesystem::path exr;
  std::vector<double> seconds;  // wall time of each repeat
  std::string error;            // non-empty: the render failed (and why)
};

struct RegressRenderSettings {
  std::filesystem::path renderer;
  std::filesystem::path out_dir;
  std::optional<unsigned long long> seed;
  std::optional<int> threads;
  int repeats = 1;
};

// Renders `scene` at `frame` (`label` names the output file) with the
// variance of the beauty and every layer (the noise model of the comparison).
SuiteRender render_suite_frame(const regress::SuiteScene& scene, int frame,
                               const std::string& label, const RegressRenderSettings& settings);

// The golden of `label` in `dir`: its EXR and its sidecar JSON (renderer
// version, scene hash, spp, render times, the beauty's histogram).
std::filesystem::path golden_image(const std::filesystem::path& dir, const std::string& label);
std::filesystem::path golden_sidecar(const std::filesystem::path& dir, const std::string& label);

// Moves the render into `dir` as the golden and writes its sidecar, each by
// rename. Throws std::runtime_error naming the file on failure.
void write_golden(const SuiteRender& render, const std::filesystem::path& dir);

// The golden's render time (the fastest of its repeats) from its sidecar;
// nullopt if it has none.
std::optional<double> golden_seconds(const std::filesystem::path& dir, const std::string& label);

}  // namespace vesper::cli
