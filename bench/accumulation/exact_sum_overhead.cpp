// What the exact fixed-point sample sums (renderer/output/exact_sum.h) cost
// against the double accumulators they replaced, measured side by side in
// one run (bench/README.md):
//   cornell/render               vesper::render of scenes/cornell, 1 thread
//   cornell/accumulate/double    the old per-pixel accumulation (double +=, float(acc/n))
//   cornell/accumulate/fixed     the new one (to_fixed, __int128 +=, exact_mean)
// The accumulation runs on the cornell render's own sample values (RGBA of
// every camera sample, recorded once with trace_path), pixel by pixel as
// render() does; `--channels 40` replays them over 40 channels (a frame with
// layers and AOVs). The summary reports (fixed - double) / render: the share
// of the render's time the exact sums add.
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "renderer/core/accel.h"
#include "renderer/integrator/path_tracer.h"
#include "renderer/output/exact_sum.h"
#include "renderer/render/render.h"
#include "renderer/sampling/pixel_filter.h"
#include "renderer/sampling/sampler.h"
#include "renderer/scene/scene_loader.h"

namespace {

using namespace vesper;

int g_spp = 8;
int g_width = 0, g_height = 0;
std::vector<float> g_values;  // (pixel * spp + sample) * 4 + {r, g, b, alpha}
const Scene* g_scene = nullptr;
std::vector<float> g_out;

void record_samples(const Scene& scene) {
  g_width = scene.film.width;
  g_height = scene.film.height;
  g_values.resize(size_t(g_width) * size_t(g_height) * size_t(g_spp) * 4);
  PathTracerOptions pt;
  pt.max_depth = scene.render.max_depth;
  set_flush_to_zero();
  size_t k = 0;
  for (int y = 0; y < g_height; ++y)
    for (int x = 0; x < g_width; ++x)
      for (int s = 0; s < g_spp; ++s) {
        Sampler sampler(scene.render.seed, uint64_t(y) * uint64_t(g_width) + uint64_t(x),
                        uint64_t(s));
        const Vec2 offset = sample_pixel_filter(scene.film.filter, sampler.next2());
        const Vec2 u_lens = sampler.next2();
        const Ray ray = scene.camera.generate_ray(float(x) + 0.5f + offset.x,
                                                  float(y) + 0.5f + offset.y, u_lens);
        const PathResult r = trace_path(scene, ray, sampler, pt);
        g_values[k++] = r.radiance.r;
        g_values[k++] = r.radiance.g;
        g_values[k++] = r.radiance.b;
        g_values[k++] = r.alpha;
      }
}

// Replays every pixel's samples into `channels` accumulators, as render() does.
template <typename Acc, typename Add, typename Out>
void accumulate(int channels, Add add, Out out) {
  std::vector<Acc> acc(static_cast<size_t>(channels));
  const size_t pixels = size_t(g_width) * size_t(g_height);
  g_out.resize(pixels * size_t(channels));
  for (size_t p = 0; p < pixels; ++p) {
    std::fill(acc.begin(), acc.end(), Acc(0));
    const float* v = &g_values[p * size_t(g_spp) * 4];
    for (int s = 0; s < g_spp; ++s, v += 4)
      for (int c = 0; c < channels; ++c) add(acc[size_t(c)], v[c & 3]);
    for (int c = 0; c < channels; ++c)
      g_out[p * size_t(channels) + size_t(c)] = out(acc[size_t(c)]);
  }
  benchmark::DoNotOptimize(g_out.data());
  benchmark::ClobberMemory();
}

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

void BM_render(benchmark::State& state) {
  RenderOptions o;
  o.threads = 1;
  o.spp = g_spp;
  for (auto _ : state) {
    // One thread: the arena's only slot is this thread, whose CPU time is the
    // render's (robust against other processes on a shared machine).
    const double t0 = thread_cpu_seconds();
    const RenderResult r = render(*g_scene, o);
    benchmark::DoNotOptimize(r.image.pixels.data());
    state.SetIterationTime(thread_cpu_seconds() - t0);
  }
}

void BM_double(benchmark::State& state) {
  const int channels = int(state.range(0));
  const double inv = 1.0 / double(g_spp);
  for (auto _ : state)
    accumulate<double>(
        channels, [](double& a, float v) { a += v; }, [inv](double a) { return float(a * inv); });
}

void BM_fixed(benchmark::State& state) {
  const int channels = int(state.range(0));
  const int64_t n = g_spp;
  for (auto _ : state)
    accumulate<ExactSum>(
        channels, [](ExactSum& a, float v) { a += to_fixed(v); },
        [n](ExactSum a) { return exact_mean(a, n); });
}

// Captures the per-iteration real times of the runs for the summary.
class Summary : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
      const std::string name = r.benchmark_name();
      // Manual time (the render's thread CPU time) or this thread's CPU time.
      const double t = (name.find("/render") != std::string::npos ? r.GetAdjustedRealTime()
                                                                  : r.GetAdjustedCPUTime()) *
                       1e-9;
      times[name].push_back(t);
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, std::vector<double>> times;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int channels = 4;
  std::vector<char*> args{argv[0]};
  bool has_reps = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      g_spp = 1;
    } else if (std::strcmp(argv[i], "--channels") == 0 && i + 1 < argc) {
      channels = std::atoi(argv[++i]);
    } else {
      if (std::strncmp(argv[i], "--benchmark_repetitions", 23) == 0) has_reps = true;
      args.push_back(argv[i]);
    }
  }
  static char reps[] = "--benchmark_repetitions=5";
  static char interleave[] = "--benchmark_enable_random_interleaving=true";
  if (!has_reps) {
    args.push_back(reps);
    args.push_back(interleave);
  }
  int n = int(args.size());
  benchmark::Initialize(&n, args.data());

  const Scene scene =
      build_scene(load_scene(std::string(VESPER_SOURCE_DIR) + "/scenes/cornell/scene.json"));
  g_scene = &scene;
  record_samples(scene);
  std::fprintf(stderr, "cornell %dx%d, %d spp, %d channels accumulated\n", g_width, g_height, g_spp,
               channels);

  benchmark::RegisterBenchmark("cornell/render", BM_render)
      ->UseManualTime()
      ->Unit(benchmark::kNanosecond)
      ->Iterations(1);
  benchmark::RegisterBenchmark("cornell/accumulate/double", BM_double)
      ->Arg(channels)
      ->Unit(benchmark::kNanosecond);
  benchmark::RegisterBenchmark("cornell/accumulate/fixed", BM_fixed)
      ->Arg(channels)
      ->Unit(benchmark::kNanosecond);
  Summary summary;
  benchmark::RunSpecifiedBenchmarks(&summary);

  auto find = [&](const std::string& prefix) {
    for (const auto& [k, v] : summary.times)
      if (k.rfind(prefix, 0) == 0) return median(v);
    return 0.0;
  };
  const double render_s = find("cornell/render"), double_s = find("cornell/accumulate/double"),
               fixed_s = find("cornell/accumulate/fixed");
  std::printf(
      "\nsummary (medians of thread CPU time, 1 thread, cornell %dx%d at %d spp, %d channels)\n",
      g_width, g_height, g_spp, channels);
  std::printf("  render                    %10.4f s\n", render_s);
  std::printf("  accumulate, double        %10.4f s  (%.2f%% of the render)\n", double_s,
              100.0 * double_s / render_s);
  std::printf("  accumulate, fixed point   %10.4f s  (%.2f%% of the render)\n", fixed_s,
              100.0 * fixed_s / render_s);
  std::printf("  fixed / double accumulation      %.2fx\n", fixed_s / double_s);
  std::printf("  exact sums' extra cost: (fixed - double) / render = %+.2f%%\n",
              100.0 * (fixed_s - double_s) / render_s);
  benchmark::Shutdown();
  return 0;
}
