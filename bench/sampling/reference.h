#pragma once
// A high-spp reference image for time-against-error measurements, rendered
// once and kept in a cache directory under a name made of everything that
// decides its pixels (scene hash, renderer version, film size, spp, seed).
#include <filesystem>
#include <optional>

#include "renderer/output/layered_image.h"
#include "renderer/scene/scene.h"

namespace vesper::bench {

struct Reference {
  LayeredImage image;  // R, G, B, A, variance.R/G/B
  // The reference's own contribution to a measured relMSE: mean over pixels
  // and R, G, B of var(mean) / (r² + 0.01), from its variance channels.
  double noise_floor = 0;
  double seconds = 0;  // render time (0 when loaded from the cache)
  bool from_cache = false;
};

// Loads the reference from `cache` (when given and present) or renders it at
// `spp` with `seed` and stores it there.
Reference load_or_render_reference(const Scene& scene, int spp, uint64_t seed,
                                   const std::optional<std::filesystem::path>& cache);

}  // namespace vesper::bench
