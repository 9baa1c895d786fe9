#pragma once
// The contract between `vesper bench` and the renderers it measures: Vesper
// in process, and peers (Blender Cycles) run as a child process. Each is
// asked for one scene at one spp and seed and returns the beauty and how long
// it took; the runner does the rest (references, relMSE, curves).
#include <cstdint>
#include <functional>
#include <string>

#include "renderer/output/layered_image.h"

namespace vesper::measure {

// One scene of the benchmark set (bench/scenes.json), resolved.
struct BenchScene {
  std::string name;           // unique in the set, e.g. "fog-shafts"
  std::string scene_path;     // absolute path of the vesper-scene/1 file
  std::string kind;           // "surface" or "volume" (which Cycles goal applies)
  int width = 0, height = 0;  // the film size measured (overrides film.width/height)
};

struct RenderedImage {
  LayeredImage image;         // R, G, B at least (scene-linear, no alpha needed)
  double render_seconds = 0;  // the renderer's own time for the samples (no start-up, no I/O)
  double wall_seconds = 0;    // everything the caller waited for (process start, load, BVH, write)
};

struct BenchRenderer {
  std::string name;  // "vesper", "cycles"
  // Changes whenever a cached reference of this renderer must not be reused:
  // the renderer's version and, for a peer, the translation script's hash.
  std::string cache_key;
  // Renders `scene` at `spp` samples per pixel with `seed` on `threads`
  // threads. Throws std::runtime_error naming the scene and the renderer on
  // failure (a peer's stderr tail included).
  std::function<RenderedImage(const BenchScene& scene, int spp, uint64_t seed, int threads)> render;
};

}  // namespace vesper::measure
