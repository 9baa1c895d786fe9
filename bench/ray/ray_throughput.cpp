// Ray throughput: how much of the machine's raw Embree ray rate the path
// tracer keeps, measured side by side in one run (bench/README.md).
//
// For each scene (the Cornell box from scenes/cornell, and a >= 1M-triangle
// displaced sphere built here) the benchmark measures, with the same thread
// count as the render (all hardware threads, TBB):
//   raw/intersect1/coherent     rtcIntersect1 on primary camera rays, tile order
//   raw/intersect1/incoherent   rtcIntersect1, origins on random surface points,
//                               uniformly random directions
//   raw/intersect1/incoh_volume rtcIntersect1, origins uniform in the geometry bounds
//   raw/occluded1/incoherent    rtcOccluded1 on the incoherent rays (shadow-ray kind)
//   raw/intersect16/coherent    rtcIntersect16 on 4x4 pixel packets: an upper bound
//   accel/intersect/*           the same rays through vesper::Accel::intersect
//   tracer/render               vesper::render: RenderStats::rays / RenderStats::seconds
// and prints a summary with tracer rays/s divided by the raw rates.
//
// The raw Embree scene is a vesper::EmbreeScene (the renderer's own builder,
// on its own device) of the render-space geometry inside the scene's
// vesper::Accel, so raw and Accel rays always meet the same surfaces.
//
// Files: scenes.* (scenes and ray sets), raw_rays.* (the tracing loops),
// summary.* (the report); this file times them with Google Benchmark.
//
// Quick mode for CI smoke runs: --quick or VESPER_BENCH_QUICK=1 (small ray sets,
// a 65k-triangle mesh instead of 1M, 1 spp, one iteration each).
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "bench/ray/raw_rays.h"
#include "bench/ray/scenes.h"
#include "bench/ray/summary.h"
#include "renderer/render/render.h"
#include "renderer/scene/scene_loader.h"

namespace {

using vesper::bench::BenchScene;

struct Settings {
  bool quick = false;
  size_t rays_per_set = size_t(1) << 20;  // rays traced per benchmark iteration
  int mesh_segments = 1024;               // displaced sphere: 2 * segments * (rings - 1) triangles
  int mesh_rings = 513;
  int spp = 8;  // tracer samples per pixel
  int render_iterations = 2;
  double raw_min_time = 0.5;  // seconds per raw measurement
  int threads = 0;            // resolved to all hardware threads
};
Settings g_settings;

// Accumulated inside one run of a benchmark function.
struct Measure {
  double rays = 0, seconds = 0, hits = 0, cpu_seconds = 0;
  double hit_fraction() const { return rays > 0 ? hits / rays : 0; }
};

// User + system CPU time of the whole process (all threads), in seconds.
double process_cpu_seconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

using Clock = std::chrono::steady_clock;

template <typename Run>  // Run() -> hits; traces `rays` rays
void bench_rays(benchmark::State& state, size_t rays, Run run) {
  Measure m;
  for (auto _ : state) {
    const double c0 = process_cpu_seconds();
    const auto t0 = Clock::now();
    const uint64_t hits = run();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    m.cpu_seconds += process_cpu_seconds() - c0;
    state.SetIterationTime(dt);
    benchmark::DoNotOptimize(hits);
    m.rays += double(rays);
    m.seconds += dt;
    m.hits += double(hits);
  }
  state.counters["rays/s"] = benchmark::Counter(m.rays, benchmark::Counter::kIsRate);
  state.counters["hit%"] = 100.0 * m.hit_fraction();
  state.counters["cores"] = m.seconds > 0 ? m.cpu_seconds / m.seconds : 0;
  state.counters["threads"] = g_settings.threads;
}

void bench_render(benchmark::State& state, const BenchScene& bs) {
  vesper::RenderOptions opt;
  opt.threads = g_settings.threads;
  opt.spp = g_settings.spp;
  opt.aovs = std::vector<vesper::Aov>{};
  Measure m;
  double samples = 0;
  for (auto _ : state) {
    const double c0 = process_cpu_seconds();
    const vesper::RenderResult r = vesper::render(bs.scene, opt);
    m.cpu_seconds += process_cpu_seconds() - c0;
    state.SetIterationTime(r.stats.seconds);
    m.rays += double(r.stats.rays);
    m.seconds += r.stats.seconds;
    samples += double(r.stats.camera_samples);
    benchmark::DoNotOptimize(r.image.pixels.data());
  }
  state.counters["rays/s"] = benchmark::Counter(m.rays, benchmark::Counter::kIsRate);
  state.counters["rays/sample"] = samples > 0 ? m.rays / samples : 0;
  state.counters["cores"] = m.seconds > 0 ? m.cpu_seconds / m.seconds : 0;
  state.counters["spp"] = g_settings.spp;
  state.counters["threads"] = g_settings.threads;
}

void register_scene(const BenchScene& bs) {
  const std::string& s = bs.name;
  auto reg = [&](const std::string& what, size_t rays, auto run) {
    auto* b = benchmark::RegisterBenchmark(
        (s + "/" + what).c_str(), [=](benchmark::State& st) { bench_rays(st, rays, run); });
    b->UseManualTime()->Unit(benchmark::kMillisecond);
    if (g_settings.quick)
      b->Iterations(1);
    else
      b->MinTime(g_settings.raw_min_time);
  };
  using namespace vesper::bench;
  const RTCScene rs = bs.raw->scene();
  const vesper::Accel* accel = bs.scene.accel.get();
  const auto *coh = &bs.coherent, *inc = &bs.incoherent, *vol = &bs.incoherent_volume;
  const int t = g_settings.threads;
  reg("raw/intersect1/coherent", coh->size(), [=] { return raw_intersect1(rs, *coh, t); });
  reg("raw/intersect1/incoherent", inc->size(), [=] { return raw_intersect1(rs, *inc, t); });
  reg("raw/intersect1/incoh_volume", vol->size(), [=] { return raw_intersect1(rs, *vol, t); });
  reg("raw/occluded1/incoherent", inc->size(), [=] { return raw_occluded1(rs, *inc, t); });
  reg("raw/intersect16/coherent", coh->size(), [=] { return raw_intersect16(rs, *coh, t); });
  reg("accel/intersect/coherent", coh->size(), [=] { return accel_intersect(*accel, *coh, t); });
  reg("accel/intersect/incoherent", inc->size(), [=] { return accel_intersect(*accel, *inc, t); });
  auto* r = benchmark::RegisterBenchmark((s + "/tracer/render").c_str(),
                                         [&bs](benchmark::State& st) { bench_render(st, bs); });
  r->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(g_settings.quick ? 1 : g_settings.render_iterations);
}

bool env_quick() {
  const char* v = std::getenv("VESPER_BENCH_QUICK");
  return v && *v && std::strcmp(v, "0") != 0;
}

}  // namespace

int main(int argc, char** argv) {
  // --quick is ours; strip it before Google Benchmark sees the arguments.
  std::vector<char*> args;
  bool quick = env_quick();
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else
      args.push_back(argv[i]);
  }
  // Defaults: 3 repetitions, randomly interleaved, so that load from other
  // processes hits raw and tracer measurements alike; the summary takes medians.
  // Both can be overridden on the command line.
  auto has_flag = [&](const char* prefix) {
    return std::any_of(args.begin(), args.end(), [&](const char* a) {
      return std::strncmp(a, prefix, std::strlen(prefix)) == 0;
    });
  };
  static char reps_flag[] = "--benchmark_repetitions=3";
  static char interleave_flag[] = "--benchmark_enable_random_interleaving=true";
  if (!quick && !has_flag("--benchmark_repetitions")) args.push_back(reps_flag);
  if (!quick && !has_flag("--benchmark_enable_random_interleaving"))
    args.push_back(interleave_flag);
  int nargs = int(args.size());
  if (quick) {
    g_settings.quick = true;
    g_settings.rays_per_set = size_t(1) << 14;
    g_settings.mesh_segments = 256;
    g_settings.mesh_rings = 129;
    g_settings.spp = 1;
  }
  g_settings.threads =
      tbb::this_task_arena::max_concurrency();  // what vesper::render uses for threads = 0

  benchmark::Initialize(&nargs, args.data());
  if (benchmark::ReportUnrecognizedArguments(nargs, args.data())) return 1;

  std::vector<std::unique_ptr<BenchScene>> scenes;
  try {
    const auto t0 = Clock::now();
    const size_t n = g_settings.rays_per_set;
    scenes.push_back(vesper::bench::make_bench_scene(
        "cornell",
        vesper::load_scene(std::string(VESPER_SOURCE_DIR) + "/scenes/cornell/scene.json"), n));
    scenes.push_back(vesper::bench::make_bench_scene(
        "dense-mesh",
        vesper::bench::dense_mesh_scene(g_settings.mesh_segments, g_settings.mesh_rings), n));
    std::fprintf(stderr, "scenes built and ray sets generated in %.2f s\n",
                 std::chrono::duration<double>(Clock::now() - t0).count());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vesper_bench: %s\n", e.what());
    return 1;
  }
  std::vector<vesper::bench::SceneLine> lines;
  for (const auto& s : scenes) {
    register_scene(*s);
    lines.push_back({s->name, s->info});
  }
  vesper::bench::SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  reporter.print_summary(lines, g_settings.threads, g_settings.quick);
  return 0;
}
