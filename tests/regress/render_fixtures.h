#pragma once
// Scenes and renders for the regression tests: small films, the variance
// AOV on, in-process renders (renderer/render/frame.h).
#include <string>

#include "renderer/render/frame.h"
#include "renderer/scene/scene_loader.h"
#include "tests/renderer/scene_fixtures.h"

namespace vesper::test {

// Every layer of the scene, the beauty's variance channels (and with
// `layer_variance` every layer's, <layer>.variance.R/G/B), a fixed seed.
inline LayeredImage render_with_variance(const SceneDescription& d, uint64_t seed,
                                         bool layer_variance = false) {
  RenderOptions o;
  o.seed = seed;
  o.aovs = std::vector<Aov>{Aov::Variance};
  o.layer_variance = layer_variance;
  return render_frame(d, o).image;
}

// The small Cornell box with a "surfaces" layer (surface-first paths) and the back wall in its own
// material "back" (same albedo as the other white walls), so a test can change it alone.
inline SceneDescription cornell(int w, int h, int spp) {
  SceneDescription d = small_cornell(w, h, spp);
  d.shapes[2].material = add_material(d, "back", DiffuseMaterialDesc{Rgb(0.73f)});
  d.layers.push_back({"surfaces", PathSelection::Surface, std::nullopt, std::nullopt});
  return d;
}

// scenes/fog-shafts at a small film (its camera, aspect 4:3), with a "fog"
// layer (volume-first paths).
inline SceneDescription fog_shafts(int w, int spp) {
  SceneDescription d = load_scene(std::string(VESPER_SOURCE_DIR) + "/scenes/fog-shafts/scene.json");
  d.film.width = w;
  d.film.height = w * 3 / 4;
  d.render.spp = spp;
  d.layers.push_back({"fog", PathSelection::Volume, std::nullopt, std::nullopt});
  return d;
}

}  // namespace vesper::test
