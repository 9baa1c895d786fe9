#pragma once
// Renders a scene into a layered float image: tiles over TBB threads, each
// pixel's samples depending only on (seed, pixel, sample index).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "renderer/output/exact_sum.h"
#include "renderer/output/layered_image.h"
#include "renderer/scene/scene.h"

namespace vesper {

// A layer computed in the beauty's pass: the contributions of the paths
// whose first event matches `paths` and whose light group is in `lights`.
struct LayerSelection {
  std::string name;
  PathSelection paths = PathSelection::All;
  std::optional<std::vector<std::string>> lights;  // group names; unset = all
  bool alpha = false;  // also write <name>.A = 1 - camera-ray transmittance
};

struct RenderOptions {
  int threads = 0;                       // 0 = all hardware threads
  std::optional<int> spp;                // overrides render.spp
  std::optional<uint64_t> seed;          // overrides render.seed
  std::optional<std::vector<Aov>> aovs;  // overrides render.aovs
  // Renders sample indices [sample_begin, sample_end) of the pixel estimate;
  // sample_end defaults to spp. At most kMaxExactSamples samples per range
  // (std::invalid_argument otherwise). Pixels are exact_mean() of fixed-point
  // sums (output/exact_sum.h), so disjoint ranges merge bitwise through
  // their sums (output/partial_io.h).
  int sample_begin = 0;
  std::optional<int> sample_end;
  // Also return the exact per-pixel sample sums (RenderResult::sums), for a
  // partial render. Costs 16 bytes per pixel and channel; off by default.
  bool keep_sums = false;
  bool equiangular = true;  // equiangular sampling toward point/spot lights in homogeneous media
  std::vector<LayerSelection> layers;  // path-selection layers, same pass as the beauty
  // Called from worker threads after each tile (must be thread-safe).
  std::function<void(size_t tiles_done, size_t tiles_total)> on_progress;
};

struct RenderStats {
  double seconds = 0;
  uint64_t camera_samples = 0;
  uint64_t rays = 0;               // intersection + occlusion queries
  uint64_t nonfinite_samples = 0;  // NaN/Inf path values caught and dropped
};

struct RenderResult {
  LayeredImage image;
  RenderStats stats;
  // With RenderOptions::keep_sums: the fixed-point sample sums, laid out like
  // image.pixels (pixel-major, image.channels order); image.pixels[i] ==
  // exact_mean(sums[i], sample count). Empty otherwise.
  std::vector<ExactSum> sums;
};

RenderResult render(const Scene& scene, const RenderOptions& options = {});

}  // namespace vesper
