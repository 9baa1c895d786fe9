// Cost of the layer machinery, measured side by side in one run on the
// night-room scene: no layers, path-selection layers + transport AOVs (same
// pass), everything including the dense-fog variant (a second pass), and
// Cryptomatte alone (per-pixel first-hit counts, no layers).
//
//   ./build/bench/vesper_layers_bench [--quick]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/render/frame.h"
#include "renderer/scene/scene_loader.h"

using namespace vesper;

int main(int argc, char** argv) {
  bool quick = std::getenv("VESPER_BENCH_QUICK") != nullptr;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
  const auto file = std::filesystem::path(VESPER_SOURCE_DIR) / "scenes/night-room/scene.json";
  SceneDescription full = load_scene(file);
  full.film.width = quick ? 40 : 200;
  full.film.height = quick ? 25 : 125;
  const int spp = quick ? 1 : 8, repeats = quick ? 1 : 5;

  SceneDescription none = full;
  none.layers.clear();
  none.render.aovs.clear();
  SceneDescription same_pass = full;
  std::erase_if(same_pass.layers, [](const LayerDesc& l) { return l.variant.has_value(); });
  same_pass.render.aovs = {Aov::Emission,       Aov::DiffuseDirect,    Aov::DiffuseIndirect,
                           Aov::SpecularDirect, Aov::SpecularIndirect, Aov::VolumeDirect,
                           Aov::VolumeIndirect};
  SceneDescription all = same_pass;
  all.layers = full.layers;
  SceneDescription crypto = none;
  crypto.render.aovs = {Aov::Cryptomatte};

  struct Case {
    const char* name;
    const SceneDescription* desc;
    double seconds = 0;
    size_t channels = 0;
  };
  std::vector<Case> cases = {{"no layers, no AOVs", &none},
                             {"4 layers + 7 transport AOVs (1 pass)", &same_pass},
                             {"... + rays_dense variant (2 passes)", &all},
                             {"cryptomatte, no layers", &crypto}};
  RenderOptions o;
  o.spp = spp;
  for (auto& c : cases) render_frame(*c.desc, o);  // warm-up
  for (int r = 0; r < repeats; ++r)
    for (auto& c : cases) {  // interleaved: load drifts hit every case alike
      const FrameResult f = render_frame(*c.desc, o);
      c.seconds += f.stats.seconds / repeats;
      c.channels = f.image.channel_count();
    }
  std::printf("night-room %dx%d, %d spp, mean of %d interleaved runs\n", full.film.width,
              full.film.height, spp, repeats);
  std::printf("  %-40s %9s %9s %9s\n", "configuration", "channels", "time [s]", "ratio");
  for (const auto& c : cases)
    std::printf("  %-40s %9zu %9.3f %8.2fx\n", c.name, c.channels, c.seconds,
                c.seconds / cases[0].seconds);
  return 0;
}
