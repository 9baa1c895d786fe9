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
#include <optional>
#include <string>
#include <utility>
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
  bool equiangular_in_cone = true;
  std::optional<LightSelection> light_selection{};  // default: the scene's
  std::optional<bool> light_vertices{};             // default: RenderOptions' automatic choice
  bool sun_shafts = true;
  std::optional<int> light_traced_from{};  // default: RenderOptions' automatic choice
  bool photon_merging = false;             // opt-in, biased
  std::optional<double> photon_radius{};   // default: photon_radius's rule
};

struct Measurement {
  double seconds = 0, relmse = 0,
         relmse_se = 0;  // relMSE is heavy-tailed: report its standard error
  double fireflies = 0;  // firefly_fraction (image_metrics.h), mean over the runs
};

// The scene as configuration c builds it.
Scene build_for(const SceneDescription& desc, const Config& c) {
  SceneBuildOptions build;
  build.media.majorant_grid = c.majorant_grid;
  SceneDescription d = desc;
  if (c.light_selection) d.render.light_selection = *c.light_selection;
  return build_scene(d, build);
}

// Configuration c's render options for run r (its seed).
RenderOptions options_for(const Config& c, int spp, int r) {
  RenderOptions o;
  o.spp = spp;
  o.seed = 1000 + uint64_t(r);
  o.equiangular = c.equiangular;
  o.equiangular_in_cone = c.equiangular_in_cone;
  o.light_vertices = c.light_vertices;
  o.sun_shafts = c.sun_shafts;
  o.light_traced_from = c.light_traced_from;
  o.photon_merging = c.photon_merging;
  o.photon_radius = c.photon_radius;
  return o;
}

// Runs every configuration `repeats` times, interleaved so that machine load
// drifts affect all of them alike.
std::vector<Measurement> measure_all(const SceneDescription& desc,
                                     const std::vector<Config>& configs,
                                     const LayeredImage& reference, int spp, int repeats) {
  std::vector<Scene> scenes;
  for (const Config& c : configs) scenes.push_back(build_for(desc, c));
  std::vector<Measurement> ms(configs.size());
  std::vector<double> sum2(configs.size(), 0.0);
  for (int r = 0; r < repeats; ++r) {
    for (size_t i = 0; i < configs.size(); ++i) {
      const RenderResult res = render(scenes[i], options_for(configs[i], spp, r));
      const double e = relative_mse(res.image, reference);
      ms[i].fireflies += firefly_fraction(res.image);
      ms[i].seconds += res.stats.seconds;
      ms[i].relmse += e;
      sum2[i] += e * e;
    }
  }
  for (size_t i = 0; i < configs.size(); ++i) {
    Measurement& m = ms[i];
    m.seconds /= repeats;
    m.relmse /= repeats;
    m.fireflies /= repeats;
    if (repeats > 1)
      m.relmse_se =
          std::sqrt(std::max(0.0, sum2[i] / repeats - m.relmse * m.relmse) / (repeats - 1));
  }
  return ms;
}

// The transport AOVs that split the beauty by what the path did (their sum
// is the beauty, less what the camera sees directly: lights, emission).
const std::vector<std::pair<Aov, const char*>> kPathKinds = {
    {Aov::VolumeDirect, "volume_direct"},     {Aov::VolumeIndirect, "volume_indirect"},
    {Aov::DiffuseDirect, "diffuse_direct"},   {Aov::DiffuseIndirect, "diffuse_indirect"},
    {Aov::SpecularDirect, "specular_direct"}, {Aov::SpecularIndirect, "specular_indirect"}};

// Where the first configuration's error lies: each path kind's squared
// error against the reference's same AOV, over the reference beauty's
// r^2 + 0.01 (relMSE's weights), averaged over `runs` renders. The kinds'
// shares sum to the relMSE less the covariance between kinds. Not timed.
void print_error_by_path_kind(const SceneDescription& desc, const Config& c,
                              const LayeredImage& reference, int spp, int runs) {
  const Scene scene = build_for(desc, c);
  std::vector<double> share(kPathKinds.size(), 0.0);
  for (int r = 0; r < runs; ++r) {
    RenderOptions o = options_for(c, spp, r);
    o.aovs = std::vector<Aov>{};
    for (const auto& k : kPathKinds) o.aovs->push_back(k.first);
    const LayeredImage img = render(scene, o).image;
    for (size_t k = 0; k < kPathKinds.size(); ++k)
      for (const char* ch : {".R", ".G", ".B"}) {
        const std::string name = std::string(kPathKinds[k].second) + ch;
        const int ci = img.channel_index(name), cr = reference.channel_index(name);
        const int cb = reference.channel_index(std::string(1, ch[1]));
        if (ci < 0 || cr < 0 || cb < 0) continue;
        double sum = 0;
        for (int y = 0; y < img.height; ++y)
          for (int x = 0; x < img.width; ++x) {
            const double v = img.at(x, y, size_t(ci)), ref = reference.at(x, y, size_t(cr));
            const double b = reference.at(x, y, size_t(cb));
            sum += (v - ref) * (v - ref) / (b * b + 0.01);
          }
        share[k] += sum / (3.0 * img.width * img.height * runs);
      }
  }
  std::printf("  error by path kind (%s, %d runs):", c.name.c_str(), runs);
  for (size_t k = 0; k < kPathKinds.size(); ++k)
    if (share[k] >= 5e-5) std::printf(" %s %.4f", kPathKinds[k].second, share[k]);
  std::printf("\n");
}

struct Setup {
  int width = 160, height = 120, ref_spp = 1024, spp = 16, repeats = 8;
};

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
               const std::vector<Config>& configs, Setup setup, bool quick) {
  SceneDescription desc;
  try {
    desc = load_scene(file);
  } catch (const std::exception& e) {
    std::printf("%s: skipped (%s)\n\n", label.c_str(), e.what());
    return;
  }
  if (quick) setup = {48, 36, 32, 4, 1};
  desc.film.width = setup.width;
  desc.film.height = setup.height;

  std::printf("%s (%dx%d, reference %d spp, measured at %d spp x %d runs)\n", label.c_str(),
              desc.film.width, desc.film.height, setup.ref_spp, setup.spp, setup.repeats);
  RenderOptions ro;
  ro.spp = setup.ref_spp;
  ro.seed = 7;
  // With the path-kind AOVs (the beauty is bit for bit the same).
  ro.aovs = std::vector<Aov>{};
  for (const auto& k : kPathKinds) ro.aovs->push_back(k.first);
  const RenderResult ref = render(build_scene(desc), ro);
  std::printf("  reference: %.1f s\n", ref.stats.seconds);
  std::printf("  %-50s %9s %19s %10s %14s\n", "configuration", "time [s]", "relMSE (+- se)",
              "fireflies", "equal-error t");
  measure_all(desc, configs, ref.image, setup.spp, 1);  // warm-up: page in the grid, threads
  const std::vector<Measurement> ms =
      measure_all(desc, configs, ref.image, setup.spp, setup.repeats);
  const double base = ms[0].seconds * ms[0].relmse;
  for (size_t i = 0; i < configs.size(); ++i)
    std::printf("  %-50s %9.3f %10.4f +- %6.4f %9.4f%% %13.2fx\n", configs[i].name.c_str(),
                ms[i].seconds, ms[i].relmse, ms[i].relmse_se, 100.0 * ms[i].fireflies,
                ms[i].seconds * ms[i].relmse / base);
  print_error_by_path_kind(desc, configs[0], ref.image, setup.spp, std::min(setup.repeats, 4));
  std::printf(
      "  (equal-error t: time to reach the first row's error, relative to it; lower is "
      "better. fireflies: pixels > 10x their 5x5 median)\n\n");
}

bool wanted(const std::vector<std::string>& only, const std::string& name) {
  return only.empty() || std::find(only.begin(), only.end(), name) != only.end();
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = std::getenv("VESPER_BENCH_QUICK") != nullptr;
  std::vector<std::string> only;  // scene names given on the command line
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else
      only.emplace_back(argv[i]);
  }
  const std::filesystem::path root(VESPER_SOURCE_DIR);
  const std::filesystem::path scenes = root / "scenes";
  // "Issue 11's start": the estimator the issue measured (equiangular over
  // the whole ray, light choice by power and uniformly).
  const Config start{.name = "issue 11 start (whole-ray equiangular, power_uniform)",
                     .equiangular_in_cone = false,
                     .light_selection = LightSelection::PowerUniform,
                     .light_vertices = false,
                     .sun_shafts = false,
                     .light_traced_from = 0};
  const Config lt_forced{.name = "light tracing from 2 (forced on)", .light_traced_from = 2};
  const Config lt_3{.name = "light tracing from 3", .light_traced_from = 3};
  const Config lt_off{.name = "light tracing off", .light_traced_from = 0};
  const Config lt_lv_off{.name = "light tracing off, light-vertex connections off",
                         .light_vertices = false,
                         .light_traced_from = 0};
  const Config no_lv{.name = "light-vertex connections off", .light_vertices = false};
  const Config lv_on{.name = "light-vertex connections on", .light_vertices = true};
  const Config eq_off{.name = "equiangular off", .equiangular = false};
  // Photon merging is opt-in (biased): its rows against the same exact
  // reference, the automatic radius and two fixed ones (scene units).
  const Config pm{.name = "photon merging (opt-in, biased)", .photon_merging = true};
  const Config pm_small{
      .name = "photon merging, radius 0.05", .photon_merging = true, .photon_radius = 0.05};
  const Config pm_large{
      .name = "photon merging, radius 0.3", .photon_merging = true, .photon_radius = 0.3};

  if (wanted(only, "fog-shafts"))
    run_scene("fog-shafts (homogeneous fog, spot light)", scenes / "fog-shafts/scene.json",
              {{.name = "default"},
               pm,
               pm_small,
               pm_large,
               lt_forced,
               no_lv,
               {.name = "equiangular over the whole ray", .equiangular_in_cone = false},
               eq_off,
               start},
              {}, quick);
  if (wanted(only, "point-fog"))
    run_scene(
        "point-fog (homogeneous fog, point light)", root / "bench/scenes/point-fog/scene.json",
        {{.name = "default"}, pm, pm_small, lt_3, lt_off, lt_lv_off, eq_off, start}, {}, quick);
  if (wanted(only, "smoke"))
    run_scene("smoke (shared smoke.vdb, quad + point light)", scenes / "smoke/scene.json",
              {{.name = "default (majorant grid, equiangular)"},
               pm,
               lt_forced,
               {.name = "majorant grid off (global majorant)", .majorant_grid = false},
               lv_on,
               eq_off,
               start},
              {}, quick);
  if (wanted(only, "night-room"))
    run_scene("night-room (fog, sun through a window, three candles)",
              scenes / "night-room/scene.json",
              {{.name = "default"},
               pm,
               lt_forced,
               no_lv,
               {.name = "sun shafts off", .sun_shafts = false},
               start},
              {200, 125, 1024, 64, 4}, quick);
  if (wanted(only, "lantern")) {
    const std::filesystem::path lantern = write_lantern_scene();
    run_scene("thin cloud lantern (generated cloud VDB, point light inside)", lantern,
              {{.name = "default"}, pm, lt_3, lt_off, lt_lv_off, eq_off, start}, {}, quick);
    std::filesystem::remove_all(lantern.parent_path());
  }
  return 0;
}
