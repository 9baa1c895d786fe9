// Time against error for the light choice with many lights: the linear
// spatial choice (every light weighed per choice), the light tree and
// power_uniform, side by side in one run on a generated scene: a floor with
// walls under a G x G grid of small lights (sphere, point, spot and quad
// lights in turn, powers over a decade). Each configuration renders at the
// same spp; its relMSE against a high-spp reference (another seed) and its
// time give the equal-error time ratio (time x relMSE, since relMSE ~ 1/spp).
//
//   ./build/bench/vesper_light_tree_bench [--quick] [G ...]   (default G: 4 6 8 16)
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "renderer/output/image_metrics.h"
#include "renderer/render/render.h"
#include "renderer/scene/scene.h"

using namespace vesper;

namespace {

struct Setup {
  int width = 96, height = 72, ref_spp = 1024, spp = 16, repeats = 4;
};

void add_quad(SceneDescription& d, Vec3d corner, Vec3d e1, Vec3d e2) {
  d.shapes.push_back({QuadShapeDesc{corner, e1, e2}, 0, {}});
}

// Room 16 x 16 under G x G lights at heights 1.5 to 1.9; walls 1.2 high cut
// it into cells, so most lights are shadowed from most points.
SceneDescription many_lights_scene(int grid, const Setup& setup) {
  SceneDescription d;
  d.file = "many-lights";
  d.film.width = setup.width;
  d.film.height = setup.height;
  d.render.max_depth = 4;
  d.camera.from = {0, 11, 11};
  d.camera.to = {0, 0, 0.5};
  d.camera.fov_degrees = 62;
  d.material_names.push_back("grey");
  d.materials.push_back(DiffuseMaterialDesc{Rgb(0.6f)});
  add_quad(d, {-8, 0, 8}, {16, 0, 0}, {0, 0, -16});
  for (double x : {-4.0, 0.0, 4.0}) add_quad(d, {x, 0, -6}, {0, 1.2, 0}, {0, 0, 9});
  for (double z : {-2.0, 3.0}) add_quad(d, {-7, 0, z}, {0, 1.2, 0}, {5, 0, 0});
  const double step = 15.0 / grid;
  for (int i = 0; i < grid * grid; ++i) {
    const Vec3d p{-7.5 + step * (i % grid + 0.5), 1.5 + 0.1 * (i % 5),
                  -7.5 + step * (i / grid + 0.5)};
    const float power = 0.3f * (1.f + float((i * 7) % 10));  // a decade, no pattern along rows
    LightDesc& l = d.lights.emplace_back();
    switch (i % 4) {
      case 0:
        l.light = PointLightDesc{p, Rgb(power), 0.05};
        break;
      case 1:
        l.light = PointLightDesc{p, Rgb(power), 0.0};
        break;
      case 2:
        l.light = SpotLightDesc{p, {0.2, -1, 0.1}, Rgb(2.f * power), 50, 35, 0};
        break;
      default:
        l.light = QuadLightDesc{p, {0.2, 0, 0}, {0, 0, 0.2}, Rgb(8.f * power)};  // faces down
    }
  }
  return d;
}

struct Config {
  const char* name;
  LightSelection mode;
  size_t tree_threshold;
};

struct Measurement {
  double seconds = 0, relmse = 0, relmse_se = 0;
};

// Every configuration `repeats` times, interleaved so that load drifts on
// the shared machine affect all alike.
std::vector<Measurement> measure_all(std::vector<Scene>& scenes, const LayeredImage& reference,
                                     int spp, int repeats) {
  std::vector<Measurement> ms(scenes.size());
  std::vector<double> sum2(scenes.size(), 0.0);
  for (int r = 0; r < repeats; ++r)
    for (size_t i = 0; i < scenes.size(); ++i) {
      RenderOptions o;
      o.spp = spp;
      o.seed = 1000 + uint64_t(r);
      const RenderResult res = render(scenes[i], o);
      const double e = relative_mse(res.image, reference);
      ms[i].seconds += res.stats.seconds / repeats;
      ms[i].relmse += e / repeats;
      sum2[i] += e * e;
    }
  for (size_t i = 0; i < scenes.size(); ++i)
    if (repeats > 1)
      ms[i].relmse_se =
          std::sqrt(std::max(0.0, sum2[i] / repeats - ms[i].relmse * ms[i].relmse) / (repeats - 1));
  return ms;
}

void run_grid(int grid, const Setup& setup) {
  const SceneDescription desc = many_lights_scene(grid, setup);
  const std::vector<Config> configs = {
      {"spatial, linear (every light weighed)", LightSelection::Spatial,
       std::numeric_limits<size_t>::max()},
      {"tree", LightSelection::Tree, 0},
      {"power_uniform", LightSelection::PowerUniform, 0}};
  std::vector<Scene> scenes;
  for (const Config& c : configs) {
    Scene s = build_scene(desc);
    s.light_sampler = LightSampler(s.lights, s.radius, c.mode, c.tree_threshold);
    scenes.push_back(std::move(s));
  }
  std::printf("%d lights (%dx%d, reference %d spp by the tree, measured at %d spp x %d runs)\n",
              grid * grid, setup.width, setup.height, setup.ref_spp, setup.spp, setup.repeats);
  RenderOptions ro;
  ro.spp = setup.ref_spp;
  ro.seed = 7;
  const RenderResult ref = render(scenes[1], ro);
  std::printf("  reference: %.1f s\n", ref.stats.seconds);
  std::printf("  %-40s %9s %12s %19s %14s\n", "configuration", "time [s]", "us/sample",
              "relMSE (+- se)", "equal-error t");
  measure_all(scenes, ref.image, setup.spp, 1);  // warm-up
  const std::vector<Measurement> ms = measure_all(scenes, ref.image, setup.spp, setup.repeats);
  const double samples = double(setup.width) * setup.height * setup.spp;
  const double base = ms[0].seconds * ms[0].relmse;
  for (size_t i = 0; i < configs.size(); ++i)
    std::printf("  %-40s %9.3f %12.3f %10.4f +- %6.4f %13.2fx\n", configs[i].name, ms[i].seconds,
                1e6 * ms[i].seconds / samples, ms[i].relmse, ms[i].relmse_se,
                ms[i].seconds * ms[i].relmse / base);
  std::printf("  (equal-error t: time to reach the first row's error, relative to it)\n\n");
}

}  // namespace

int main(int argc, char** argv) {
  Setup setup;
  std::vector<int> grids;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0)
      setup = {32, 24, 64, 4, 1};
    else
      grids.push_back(std::atoi(argv[i]));
  }
  if (grids.empty()) grids = {4, 6, 8, 16};
  for (int g : grids)
    if (g > 0) run_grid(g, setup);
  return 0;
}
