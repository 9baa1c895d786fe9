// Time against error for the volume estimators, measured side by side in one
// run: each configuration renders the same scene at the same spp, and its
// relMSE against a high-spp reference (rendered with a different seed) and
// its time give the equal-error time ratio (time x relMSE, since relMSE ~ 1/spp).
//
//   ./build/bench/vesper_volume_bench [--quick]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "renderer/output/image_metrics.h"
#include "renderer/render/render.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/volume/cloud.h"
#include "renderer/volume/vdb_io.h"

using namespace vesper;

namespace {

struct Config {
  std::string name;
  bool majorant_grid = true;
  bool equiangular = true;
};

struct Measurement {
  double seconds = 0, relmse = 0,
         relmse_se = 0;  // relMSE is heavy-tailed: report its standard error
};

// Runs every configuration `repeats` times, interleaved so that machine load
// drifts affect all of them alike.
std::vector<Measurement> measure_all(const SceneDescription& desc,
                                     const std::vector<Config>& configs,
                                     const LayeredImage& reference, int spp, int repeats) {
  std::vector<Scene> scenes;
  for (const Config& c : configs) {
    SceneBuildOptions build;
    build.media.majorant_grid = c.majorant_grid;
    scenes.push_back(build_scene(desc, build));
  }
  std::vector<Measurement> ms(configs.size());
  std::vector<double> sum2(configs.size(), 0.0);
  for (int r = 0; r < repeats; ++r) {
    for (size_t i = 0; i < configs.size(); ++i) {
      RenderOptions o;
      o.spp = spp;
      o.seed = 1000 + uint64_t(r);
      o.equiangular = configs[i].equiangular;
      const RenderResult res = render(scenes[i], o);
      const double e = relative_mse(res.image, reference);
      ms[i].seconds += res.stats.seconds;
      ms[i].relmse += e;
      sum2[i] += e * e;
    }
  }
  for (size_t i = 0; i < configs.size(); ++i) {
    Measurement& m = ms[i];
    m.seconds /= repeats;
    m.relmse /= repeats;
    if (repeats > 1)
      m.relmse_se =
          std::sqrt(std::max(0.0, sum2[i] / repeats - m.relmse * m.relmse) / (repeats - 1));
  }
  return ms;
}

// A thin procedural cloud (`vesper vdb cloud`'s generator, 64 voxels across)
// over a ground plane, lit by a point light inside it and a dim sky: the
// grid-medium case equiangular sampling is for. Written to a temporary
// folder (VDB + scene JSON); returns the scene file.
std::filesystem::path write_lantern_scene() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("vesper-volume-bench-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  CloudParams cloud;
  cloud.resolution = 64;
  cloud.voxel_size = 0.025;
  write_vdb_fog_volume(generate_cloud(cloud), "density", dir / "cloud.vdb");
  std::ofstream(dir / "scene.json") << R"({
  "format": "vesper-scene/1",
  "camera": {"type": "perspective", "from": [0, 0.5, 2.4], "to": [0.05, 0.3, 0], "up": [0, 1, 0],
             "fov": 40},
  "film": {"width": 160, "height": 120, "filter": "gaussian"},
  "render": {"spp": 16, "max_depth": 8, "seed": 3},
  "materials": {"ground": {"type": "diffuse", "albedo": [0.4, 0.4, 0.4]}},
  "shapes": [{"type": "quad", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10],
              "material": "ground"}],
  "lights": [{"type": "point", "position": [0.05, 0.3, 0.0], "intensity": [2, 1.6, 1.2]},
             {"type": "environment", "radiance": [0.03, 0.04, 0.06]}],
  "media": {"cloud": {"type": "vdb", "file": "cloud.vdb", "grid": "density",
                      "sigma_a": [0.05, 0.05, 0.05], "sigma_s": [1, 1, 1], "g": 0.3}}
})";
  return dir / "scene.json";
}

void run_scene(const std::string& label, const std::filesystem::path& file,
               const std::vector<Config>& configs, bool quick) {
  SceneDescription desc;
  try {
    desc = load_scene(file);
  } catch (const std::exception& e) {
    std::printf("%s: skipped (%s)\n\n", label.c_str(), e.what());
    return;
  }
  desc.film.width = quick ? 48 : 160;
  desc.film.height = quick ? 36 : 120;
  const int ref_spp = quick ? 32 : 1024, spp = quick ? 4 : 16, repeats = quick ? 1 : 8;

  std::printf("%s (%dx%d, reference %d spp, measured at %d spp x %d runs)\n", label.c_str(),
              desc.film.width, desc.film.height, ref_spp, spp, repeats);
  RenderOptions ro;
  ro.spp = ref_spp;
  ro.seed = 7;
  const RenderResult ref = render(build_scene(desc), ro);
  std::printf("  reference: %.1f s\n", ref.stats.seconds);
  std::printf("  %-36s %9s %19s %14s\n", "configuration", "time [s]", "relMSE (+- se)",
              "equal-error t");
  measure_all(desc, configs, ref.image, spp, 1);  // warm-up: page in the grid, start the threads
  const std::vector<Measurement> ms = measure_all(desc, configs, ref.image, spp, repeats);
  const double base = ms[0].seconds * ms[0].relmse;
  for (size_t i = 0; i < configs.size(); ++i)
    std::printf("  %-36s %9.3f %10.4f +- %6.4f %13.2fx\n", configs[i].name.c_str(), ms[i].seconds,
                ms[i].relmse, ms[i].relmse_se, ms[i].seconds * ms[i].relmse / base);
  std::printf(
      "  (equal-error t: time to reach the first row's error, relative to it; lower is "
      "better)\n\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = std::getenv("VESPER_BENCH_QUICK") != nullptr;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
  const std::filesystem::path scenes = std::filesystem::path(VESPER_SOURCE_DIR) / "scenes";

  run_scene("fog-shafts (homogeneous fog, spot light)", scenes / "fog-shafts/scene.json",
            {{"equiangular on", true, true}, {"equiangular off", true, false}}, quick);
  run_scene("smoke (shared smoke.vdb, quad + point light)", scenes / "smoke/scene.json",
            {{"majorant grid on, equiangular on", true, true},
             {"majorant grid off (global majorant)", false, true},
             {"majorant grid on, equiangular off", true, false}},
            quick);
  const std::filesystem::path lantern = write_lantern_scene();
  run_scene("thin cloud lantern (generated cloud VDB, point light inside)", lantern,
            {{"equiangular on", true, true}, {"equiangular off", true, false}}, quick);
  std::filesystem::remove_all(lantern.parent_path());
  return 0;
}
