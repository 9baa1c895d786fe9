#pragma once
// What a regression run found: per scene and layer a verdict, its reasons,
// the worst regions and the figures behind them. Shared by the comparison,
// report.json, the HTML report and the history database.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vesper::regress {

enum class Verdict { Pass, Regressed, Error };
const char* verdict_name(Verdict v);                          // "pass", "regressed", "error"
std::optional<Verdict> parse_verdict(std::string_view name);  // the inverse

// A tile whose difference Monte Carlo noise cannot explain.
struct Region {
  int x = 0, y = 0, width = 0, height = 0;  // pixels
  double z = 0;                             // signed Z of (new - golden) luminance mean
  double p_value = 0;                       // two-sided, before correction
  double golden_mean = 0, new_mean = 0;     // mean luminance of the tile
  double relative_change = 0;               // (new - golden) / max(|golden|, 1e-3)
};

// A pixel position.
struct Pixel {
  int x = 0, y = 0;
};

struct LayerResult {
  std::string layer;  // "beauty" for R,G,B; else the EXR layer name ("fog", "albedo", ...)
  Verdict verdict = Verdict::Pass;
  std::vector<std::string> reasons;  // one line each, e.g. "12 tiles brighter (max +4.1 %)"
  // The most significant regions, most significant first: tiles, or blocks
  // of 2x2, 4x4, ... tiles up to the whole frame (faint wide changes).
  std::vector<Region> worst;
  int tiles = 0, significant_tiles = 0;
  double max_abs_z = 0;  // over every tile and block tested
  // The smallest relative change of a tile's mean the test would have
  // flagged at this noise (median over tiles): how strong a "pass" was.
  double min_detectable_change = 0;
  // The same for the whole frame (the largest block, docs/regression.md):
  // the smallest change of the layer's mean luminance the test would flag.
  double frame_detectable_change = 0;
  double histogram_distance = 0;  // Wasserstein-1 of the luminosity histograms (log2 stops)
  // The distance noise alone reaches (paired permutations, regress/layer_checks.h):
  // a histogram regresses only beyond both this and max_histogram_distance.
  double histogram_noise = 0;
  uint64_t golden_nonfinite = 0, new_nonfinite = 0;  // NaN/Inf pixels in the layer's channels
  // Pixels NaN/Inf in the new render but finite in the golden (any → regressed),
  // and where the first of them are (row-major order, at most 16).
  uint64_t introduced_nonfinite = 0;
  std::vector<Pixel> introduced_nonfinite_at;
  bool has_variance = false;  // false: compared without noise model
  // Per-tile signed Z (row-major, tiles_x * tiles_y; 0 where untested), for
  // the significance map; `tile_size` pixels square (edge tiles smaller).
  int tile_size = 0, tiles_x = 0, tiles_y = 0;
  std::vector<float> tile_z;
  // Per tile as tile_z: 1 where the difference counts (significant after the
  // multiple-testing correction and at least min_relative_change), else 0.
  // Empty: the report takes the `significant_tiles` tiles of largest |Z|.
  std::vector<uint8_t> tile_significant;
};

struct SceneResult {
  std::string name;
  Verdict verdict = Verdict::Pass;
  std::vector<std::string> reasons;  // scene-level: errors, timing, channels added/missing
  std::vector<LayerResult> layers;
  std::vector<std::string> channels_added, channels_missing;
  double golden_seconds = 0, new_seconds = 0;  // render time (median of repeats when repeated)
  std::vector<double> new_seconds_repeats;
  bool reused = false;                  // the farm reused an identical task: nothing was rendered
  std::string golden_image, new_image;  // paths of the EXRs compared
};

struct RunResult {
  std::string suite;       // path of the suite file
  std::string started_at;  // ISO 8601 UTC
  std::string renderer_version;
  std::string server;               // the farm's URL when rendered there (--server); empty: locally
  std::string render_time_note;     // why render times were not judged; empty: they were
  Verdict verdict = Verdict::Pass;  // the worst scene verdict
  std::vector<SceneResult> scenes;
};

}  // namespace vesper::regress
