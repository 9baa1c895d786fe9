#pragma once
// Renders a scene into a layered float image: tiles over TBB threads, each
// pixel's samples depending only on (seed, pixel, sample index).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "renderer/output/crypto_film.h"
#include "renderer/output/exact_sum.h"
#include "renderer/output/film_sums.h"
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

// Most Cryptomatte ranks per type: layers 00 to 99.
inline constexpr int kMaxCryptoDepth = 200;

struct RenderOptions {
  int threads = 0;                       // 0 = all hardware threads
  std::optional<int> spp;                // overrides render.spp
  std::optional<uint64_t> seed;          // overrides render.seed
  std::optional<std::vector<Aov>> aovs;  // overrides render.aovs
  // Renders sample indices [sample_begin, sample_end) of the pixel estimate;
  // sample_end defaults to spp (max_spp with a noise target). At most
  // kMaxExactSamples samples per range (std::invalid_argument otherwise).
  // Pixels are exact_mean() of fixed-point sums (output/exact_sum.h), so
  // disjoint ranges merge bitwise through their sums (output/partial_io.h).
  // An adaptive render takes a prefix [sample_begin, sample_begin + n) of the
  // range in each pixel.
  int sample_begin = 0;
  std::optional<int> sample_end;
  // Override render.noise_target, min_spp, max_spp, time_limit (scene.h).
  std::optional<double> noise_target;
  std::optional<int> min_spp, max_spp;
  std::optional<double> time_limit;
  std::optional<double> clamp;  // overrides render.clamp (the indirect sample clamp)
  // Take exactly this many samples in each pixel (width * height counts, at
  // most the range) instead of deciding: variant layers follow the beauty's
  // adaptive counts. Not owned.
  const std::vector<int64_t>* pixel_samples = nullptr;
  // Also return the exact film state (RenderResult::film), for a partial
  // render. Costs 16 bytes per pixel and channel, 16 per pixel for the sample
  // counts and 192 per pixel for the variance's stream sums; off by default.
  bool keep_sums = false;
  // Also write `<name>.variance.R/G/B` for every RGB AOV and layer (and the
  // beauty's variance.R/G/B): 192 more bytes per pixel for each, while
  // rendering. For the regression batch's per-layer noise model.
  bool layer_variance = false;
  // Equiangular sampling toward point/spot lights in all media (MIS with
  // distance sampling); off only to measure it (bench, tests).
  bool equiangular = true;
  bool equiangular_in_cone = true;  // ... only over the part of a ray inside a spot light's cone
  bool sun_shafts = true;           // sun shafts (sun_shaft.h); off only to measure them
  // Connections to a vertex traced from point/spot lights (media only);
  // unset: where they pay off (light_vertices_pay_off, light_vertex.h).
  std::optional<bool> light_vertices;
  // Light tracing (integrator/light_tracer.h) takes the paths whose first
  // event is in a medium or on a diffuse surface and that make at least this
  // many scattering events (>= 2; PathTracerOptions::light_traced_from);
  // 0 = off; unset: where it pays off (light_tracing_pays_off). Fixed
  // sample counts only: adaptive renders and pixel_samples leave it off, as
  // does the indirect clamp (splats would bypass it).
  std::optional<int> light_traced_from;
  // Photon merging (integrator/photon_merging.h; biased, consistent): takes
  // light tracing's part of path space (in place of light tracing). Unset:
  // render.photon_merging (off by default). Needs media, a point or spot
  // light and no motion blur; otherwise the render is exact as before.
  std::optional<bool> photon_merging;
  std::optional<double> photon_radius;  // overrides render.photon_radius (scene units)
  // Ranks per Cryptomatte type (Aov::Cryptomatte): (depth + 1) / 2 RGBA layers
  // each, in [1, kMaxCryptoDepth] (std::invalid_argument otherwise).
  int cryptomatte_depth = 6;
  std::vector<LayerSelection> layers;  // path-selection layers, same pass as the beauty
  // Called from worker threads after each tile (must be thread-safe).
  std::function<void(size_t tiles_done, size_t tiles_total)> on_progress;
};

// Why sampling stopped.
enum class StopReason { Spp, NoiseTarget, MaxSpp, TimeLimit };
const char* stop_reason_name(StopReason r);

struct RenderStats {
  double seconds = 0;
  int sampling_passes = 1;
  StopReason stop_reason = StopReason::Spp;
  uint64_t camera_samples = 0;
  uint64_t rays = 0;               // intersection + occlusion queries
  uint64_t nonfinite_samples = 0;  // NaN/Inf path values caught and dropped
};

struct RenderResult {
  LayeredImage image;
  RenderStats stats;
  // With RenderOptions::keep_sums: the exact film state (sums laid out like
  // image.pixels; resolve_image(film) == image.pixels). Empty otherwise.
  FilmSums film;
  // With keep_sums and the cryptomatte AOV: its unranked counts (a partial carries them).
  std::optional<CryptoFilm> crypto;
};

RenderResult render(const Scene& scene, const RenderOptions& options = {});

// Samples per pixel of the whole frame: the spp, or max_spp (default: the
// spp) with a noise target. `options` override the scene's render settings.
int frame_spp(const RenderDesc& render, const RenderOptions& options);

// Throws std::invalid_argument naming the setting (render.min_spp /
// --min-spp, ...) when the sampling settings do not fit together.
void check_sampling_options(const RenderDesc& render, const RenderOptions& options);

}  // namespace vesper
