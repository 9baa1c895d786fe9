#pragma once
// What a job asks of every render beyond its scene and its sampling budget,
// as `vesper render` takes it: the AOVs (--aov, instead of the scene's
// render.aovs), the per-layer variance (--layer-variance), the seed (--seed,
// instead of the scene's render.seed; each frame still gets its own from it),
// a film scale (--scale) and half-float colour channels (--half). `vesper
// regress --server` needs the first four to render on the farm what it
// renders locally (docs/farm.md, "Render overrides"). Unset, a job renders as
// the scene says.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vesper {

// The largest film scale a job may ask for (as the regression suite allows).
inline constexpr double kMaxFilmScale = 4;

struct RenderOverrides {
  std::vector<std::string> aovs;  // AOV names (render.aovs's); empty: the scene's
  bool layer_variance = false;    // <layer>.variance.R/G/B for every RGB layer
  std::optional<uint64_t> seed;   // at most INT64_MAX (the store keeps it as an integer)
  std::optional<double> scale;    // film width and height times this, in (0, kMaxFilmScale]
  bool half = false;              // half-float colour channels, whatever film.pixel_type says

  bool operator==(const RenderOverrides&) const = default;
  bool empty() const { return aovs.empty() && !layer_variance && !seed && !scale && !half; }
};

// "variance,albedo": the AOV list as `--aov` takes it and the store keeps it.
std::string join_aovs(const std::vector<std::string>& aovs);
std::vector<std::string> split_aovs(const std::string& text);

// ";aovs=variance;layer_variance=1;seed=7;scale=0.25;half=1": what the
// overrides add to a job's result-reuse key (only what is set, so a job
// without overrides keeps the key it always had).
std::string overrides_key(const RenderOverrides& overrides);

}  // namespace vesper
