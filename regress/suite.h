#pragma once
// The regression suite file, `vesper-suite/1` (docs/regression.md):
// {"format": "vesper-suite/1", "scenes": [{"name": "cornell", "scene":
// "cornell/scene.json", "spp": 64, "frames": "1", "layers": ["fog"],
// "thresholds": {...}}]}. Paths are relative to the suite file.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/json_error.h"

namespace vesper::regress {

// When a difference is a regression. Defaults fit the project's own suite;
// a scene may override any of them ("thresholds" object, same keys).
struct Thresholds {
  double alpha = 1e-4;             // family-wise false-alarm rate per layer (Holm over its tiles)
  int tile_size = 16;              // pixels
  double min_relative_change = 0;  // ignore significant tile changes smaller than this
  double max_slowdown = 1.2;       // new render time / golden's, judged on repeated timings
  double max_histogram_distance = 0.05;  // Wasserstein-1 of the luminosity histograms, stops
};

struct SuiteScene {
  std::string name;             // unique in the suite; [A-Za-z0-9_.-]+
  std::filesystem::path scene;  // absolute (resolved against the suite's folder)
  std::optional<int> spp;       // exactly one of spp, noise_target
  std::optional<double> noise_target;
  std::string frames = "1";                        // frame list as `vesper up --frames` takes it
  std::optional<std::vector<std::string>> layers;  // default: every layer in the EXR
  std::optional<double> scale;  // film size factor (vesper render --scale), in (0, 4]
  Thresholds thresholds;
};

struct Suite {
  std::filesystem::path path;  // the suite file
  std::vector<SuiteScene> scenes;
};

// A rejected suite: file(), json_path() and message() as for scenes
// (common/json_error.h); what() reads "<file>: <json path>: <message>".
class SuiteError : public JsonError {
 public:
  using JsonError::JsonError;
};

// Reads and validates everything (unknown keys, types, ranges, duplicate
// names, scene files that do not exist); a SuiteError names the file and the
// JSON path ("suite.json: /scenes/2/spp: expected an integer in [1, ...]").
Suite load_suite(const std::filesystem::path& path);
// The same from the suite's text (what load_suite reads); `path` names the
// file in messages and relative scene paths resolve against its folder.
Suite parse_suite_text(const std::string& text, const std::filesystem::path& path);

}  // namespace vesper::regress
