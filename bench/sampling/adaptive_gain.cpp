// Equal-error gain of adaptive sampling (render.noise_target) over uniform
// sampling, measured side by side in one run. For each scene: a high-spp
// reference (cached), then uniform renders at a ladder of spp and adaptive
// renders at a ladder of noise targets calibrated to the same relMSE range,
// interleaved and repeated; the time each method needs for the same relMSE
// is interpolated on its log-log (time, relMSE) curve, and the ratio
// uniform / adaptive is the gain.
//
//   ./build/bench/vesper_adaptive_bench [--quick] [--scene NAME]... [--repeats N]
//       [--cache DIR | --no-cache] [--references-only] [--ref-spp N] [--maps DIR] [--min-spp N]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "bench/sampling/allocation_bound.h"
#include "bench/sampling/equal_error.h"
#include "bench/sampling/reference.h"
#include "renderer/output/exr_io.h"
#include "renderer/output/film_sums.h"
#include "renderer/output/image_metrics.h"
#include "renderer/render/render.h"
#include "renderer/scene/scene_loader.h"

using namespace vesper;
using namespace vesper::bench;

namespace {

// Large enough never to bind: every adaptive run should stop on its target.
constexpr int kUnboundMaxSpp = 1 << 16;
constexpr int kDefaultMinSpp = 16;  // render.min_spp's default (render/sampling_plan.cpp)

struct Case {
  std::string name;  // the folder under scenes/
  int width = 0, height = 0, ref_spp = 0;
  std::vector<int> spp;  // uniform ladder; the adaptive one is calibrated to it
};

struct Settings {
  bool quick = false;
  int repeats = 3;
  std::vector<std::string> scenes;
  std::optional<std::filesystem::path> cache, maps;
  std::optional<int> min_spp;
  std::optional<int> ref_spp;    // overrides the cases' (trial runs)
  bool references_only = false;  // fill the cache and stop
};

struct Run {
  double seconds = 0, cpu_seconds = 0, relmse = 0, spp = 0;
  int passes = 1;
  StopReason stop = StopReason::Spp;
};

std::vector<Case> cases(bool quick) {
  if (quick)
    return {{"cornell", 32, 32, 64, {4, 8, 16}},
            {"night-room", 40, 25, 64, {4, 8, 16}},
            {"smoke", 24, 24, 32, {4, 8, 16}}};
  const std::vector<int> ladder = {16, 24, 32, 48, 64, 96, 128};
  // The night room's fireflies keep uniform sampling's relMSE high: its
  // uniform ladder goes on to 1024 spp (so the two curves overlap at errors
  // that matter), on a smaller film, against a 32768-spp reference.
  return {{"cornell", 128, 128, 8192, ladder},
          {"night-room", 96, 60, 32768, {16, 32, 64, 128, 256, 512, 1024}},
          {"smoke", 128, 128, 8192, ladder},
          {"fog-shafts", 160, 120, 8192, ladder}};
}

// Mean over R, G, B of the pixel's relMSE term (x - r)² / (r² + 0.01).
float pixel_relmse(const LayeredImage& img, const LayeredImage& ref, int x, int y) {
  const char* beauty[3] = {"R", "G", "B"};
  double sum = 0;
  for (const char* c : beauty) {
    const double v = img.at(x, y, size_t(img.channel_index(c)));
    const double r = ref.at(x, y, size_t(ref.channel_index(c)));
    sum += (v - r) * (v - r) / (r * r + 0.01);
  }
  return float(sum / 3);
}

// Per-pixel spp and error of an adaptive render and of a uniform one, for
// looking at where the samples went (oiiotool turns the channels into PNGs).
void write_maps(const std::filesystem::path& file, const LayeredImage& adaptive,
                const LayeredImage& uniform, const LayeredImage& ref) {
  LayeredImage maps;
  maps.width = ref.width;
  maps.height = ref.height;
  maps.channels = {"spp", "err_adaptive", "err_uniform", "ref_luma"};
  maps.pixels.resize(size_t(maps.width) * size_t(maps.height) * maps.channels.size());
  const int spp = adaptive.channel_index(kSppChannel);
  for (int y = 0; y < maps.height; ++y)
    for (int x = 0; x < maps.width; ++x) {
      maps.at(x, y, 0) = adaptive.at(x, y, size_t(spp));
      maps.at(x, y, 1) = pixel_relmse(adaptive, ref, x, y);
      maps.at(x, y, 2) = pixel_relmse(uniform, ref, x, y);
      float luma = 0;
      for (const char* c : {"R", "G", "B"}) luma += ref.at(x, y, size_t(ref.channel_index(c))) / 3;
      maps.at(x, y, 3) = luma;
    }
  std::filesystem::create_directories(file.parent_path());
  write_exr(maps, file);
}

// User + system time of the whole process so far: with the wall time, how
// many cores a render kept busy (a pass with few active pixels leaves cores idle).
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto s = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return s(u.ru_utime) + s(u.ru_stime);
}

// The R, G, B sums of a rung's images over the repeats.
struct ImageSum {
  std::vector<double> rgb;
  int count = 0;
  void add(const LayeredImage& img) {
    const size_t pixels = size_t(img.width) * size_t(img.height), nc = img.channel_count();
    rgb.resize(pixels * 3, 0.0);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) rgb[p * 3 + size_t(c)] += img.pixels[p * nc + size_t(c)];
    ++count;
  }
};

// How much of a rung's relMSE is bias (nan with one repeat): the repeats'
// mean image has relMSE bias² + var / R + floor against the reference, the
// single runs bias² + var + floor on average. Uniform sampling is unbiased,
// so its figure shows the estimate's noise.
double bias_share(const ImageSum& sum, double mean_relmse, const Reference& ref) {
  const double r = sum.count;
  if (sum.count < 2) return NAN;
  LayeredImage mean;
  mean.width = ref.image.width;
  mean.height = ref.image.height;
  mean.channels = {"R", "G", "B"};
  for (double v : sum.rgb) mean.pixels.push_back(float(v / r));
  const double of_mean = relative_mse(mean, ref.image);
  return ((r * of_mean - mean_relmse) / (r - 1) - ref.noise_floor) / mean_relmse;
}

Run measure(const Scene& scene, const RenderOptions& o, const Reference& ref,
            ImageSum* sum = nullptr, LayeredImage* keep = nullptr) {
  const double cpu0 = process_cpu_seconds();
  const RenderResult r = render(scene, o);
  Run run;
  run.cpu_seconds = process_cpu_seconds() - cpu0;
  run.seconds = r.stats.seconds;
  run.relmse = relative_mse(r.image, ref.image);
  run.spp = double(r.stats.camera_samples) / (double(r.image.width) * r.image.height);
  run.passes = r.stats.sampling_passes;
  run.stop = r.stats.stop_reason;
  if (sum) sum->add(r.image);
  if (keep) *keep = r.image;
  return run;
}

// [rung][repeat], and each rung's image sums.
struct Ladder {
  std::vector<std::vector<Run>> uniform, adaptive;
  std::vector<ImageSum> uniform_sum, adaptive_sum;
};

RenderOptions uniform_options(int spp, uint64_t seed) {
  RenderOptions o;
  o.spp = spp;
  o.seed = seed;
  o.aovs = std::vector<Aov>{};
  return o;
}

RenderOptions adaptive_options(double target, uint64_t seed, std::optional<int> min_spp) {
  RenderOptions o;
  o.noise_target = target;
  o.max_spp = kUnboundMaxSpp;
  o.min_spp = min_spp;
  o.seed = seed;
  o.aovs = std::vector<Aov>{};  // variance and spp are added by the noise target
  return o;
}

// Noise targets whose adaptive renders span the relMSE range of the uniform
// ladder, so that the two curves overlap where they are compared (the cost
// of a target differs by orders of magnitude between scenes and rules): the
// uniform ladder's two ends are rendered once, then adaptive pilots at
// targets falling by sqrt(2) until one is below the uniform ladder's lowest
// error (or takes 4x its top spp); the rungs' errors are spread evenly (in
// log) over the range and their targets interpolated between the pilots.
std::vector<double> calibrate_targets(const Case& c, const Scene& scene, const Reference& ref,
                                      const Settings& s) {
  const double hi = measure(scene, uniform_options(c.spp.front(), 99), ref).relmse;
  const double lo = measure(scene, uniform_options(c.spp.back(), 99), ref).relmse;
  std::vector<CurvePoint> pilots;  // (target, relMSE): a curve with the target for the time
  for (double x = 0.8; pilots.size() < 24; x /= std::sqrt(2.0)) {
    const Run r = measure(scene, adaptive_options(x, 99, s.min_spp), ref);
    pilots.push_back({x, r.relmse});
    if (r.relmse <= lo || r.spp > 4.0 * c.spp.back()) break;
  }
  std::vector<double> targets;
  const double rungs = double(c.spp.size());
  for (size_t i = 0; i < c.spp.size(); ++i) {
    const double e = hi * std::pow(lo / hi, double(i) / std::max(1.0, rungs - 1));
    const double x = time_at_error(pilots, e);
    targets.push_back(std::isfinite(x)            ? x
                      : e > pilots.front().relmse ? pilots.front().seconds
                                                  : pilots.back().seconds);
  }
  return targets;
}

// Every rung of both ladders `repeats` times; the two methods alternate (and
// swap which goes first) so that load from other processes hits both alike.
Ladder measure_ladders(const Case& c, const std::vector<double>& targets, const Scene& scene,
                       const Reference& ref, const Settings& s) {
  const size_t rungs = c.spp.size();
  Ladder l{std::vector<std::vector<Run>>(rungs), std::vector<std::vector<Run>>(rungs),
           std::vector<ImageSum>(rungs), std::vector<ImageSum>(rungs)};
  for (int r = 0; r < s.repeats; ++r)
    for (size_t i = 0; i < rungs; ++i) {
      const uint64_t seed = 1000 + 100 * uint64_t(r) + i;
      const RenderOptions u = uniform_options(c.spp[i], seed);
      const RenderOptions a = adaptive_options(targets[i], seed, s.min_spp);
      const bool maps = s.maps && r == 0 && i == rungs / 2;
      LayeredImage ui, ai;
      const auto run_uniform = [&] {
        l.uniform[i].push_back(measure(scene, u, ref, &l.uniform_sum[i], maps ? &ui : nullptr));
      };
      const auto run_adaptive = [&] {
        l.adaptive[i].push_back(measure(scene, a, ref, &l.adaptive_sum[i], maps ? &ai : nullptr));
      };
      if ((r + int(i)) % 2 == 0) {
        run_uniform();
        run_adaptive();
      } else {
        run_adaptive();
        run_uniform();
      }
      if (maps) write_maps(*s.maps / (c.name + "-maps.exr"), ai, ui, ref.image);
    }
  return l;
}

struct Mean {
  double seconds = 0, cpu_seconds = 0, relmse = 0, relmse_se = 0, spp = 0, passes = 0;
  int not_on_target = 0;  // adaptive runs that stopped for another reason
};

Mean mean_of(const std::vector<Run>& runs) {
  Mean m;
  double sq = 0;
  const double n = double(runs.size());
  for (const Run& r : runs) {
    m.seconds += r.seconds / n;
    m.cpu_seconds += r.cpu_seconds / n;
    m.relmse += r.relmse / n;
    m.spp += r.spp / n;
    m.passes += r.passes / n;
    sq += r.relmse * r.relmse / n;
    m.not_on_target += r.stop == StopReason::MaxSpp || r.stop == StopReason::TimeLimit;
  }
  if (runs.size() > 1) m.relmse_se = std::sqrt(std::max(0.0, sq - m.relmse * m.relmse) / (n - 1));
  return m;
}

// Which time the curves use: wall clock, or the process's CPU time (steadier
// when other processes load the machine, blind to idle cores).
enum class Cost { Wall, Cpu };

// The curve of the means over the repeats, or (repeat >= 0) of one repeat.
std::vector<CurvePoint> curve(const std::vector<std::vector<Run>>& rungs, Cost cost,
                              int repeat = -1) {
  std::vector<CurvePoint> points;
  for (const std::vector<Run>& runs : rungs) {
    const Mean m = repeat >= 0 ? mean_of({runs[size_t(repeat)]}) : mean_of(runs);
    points.push_back({cost == Cost::Wall ? m.seconds : m.cpu_seconds, m.relmse});
  }
  return points;
}

// Per rung: mean wall and CPU time, relMSE (+- its standard error over the
// repeats) and the bias share of the relMSE.
void print_ladders(const Case& c, const std::vector<double>& targets, const Ladder& l,
                   const Reference& ref) {
  std::printf("  %-44s | %s\n", "uniform", "adaptive");
  std::printf("  %5s %6s %6s %17s %5s | %6s %6s %5s %6s %6s %17s %5s\n", "spp", "wall", "cpu",
              "relMSE (+- se)", "bias", "target", "spp", "passes", "wall", "cpu", "relMSE (+- se)",
              "bias");
  for (size_t i = 0; i < c.spp.size(); ++i) {
    const Mean u = mean_of(l.uniform[i]), a = mean_of(l.adaptive[i]);
    std::printf(
        "  %5d %6.2f %6.2f %8.5f +-%7.5f %5.2f | %6.3f %6.1f %5.1f %6.2f %6.2f %8.5f +-%7.5f "
        "%5.2f%s\n",
        c.spp[i], u.seconds, u.cpu_seconds, u.relmse, u.relmse_se,
        bias_share(l.uniform_sum[i], u.relmse, ref), targets[i], a.spp, a.passes, a.seconds,
        a.cpu_seconds, a.relmse, a.relmse_se, bias_share(l.adaptive_sum[i], a.relmse, ref),
        a.not_on_target ? "  (max_spp reached!)" : "");
  }
}

// Prints the equal-error ratios; returns their geometric mean (NaN if none).
double print_equal_error(const Ladder& l, int repeats, Cost cost) {
  const std::vector<CurvePoint> u = curve(l.uniform, cost), a = curve(l.adaptive, cost);
  const std::vector<double> levels = common_error_levels(u, a, 3);
  if (levels.empty()) {
    std::printf("  equal error: the two curves' relMSE ranges do not overlap\n");
    return NAN;
  }
  double log_sum = 0;
  for (double e : levels) {
    const double tu = time_at_error(u, e), ta = time_at_error(a, e);
    double lo = INFINITY, hi = -INFINITY;
    for (int r = 0; r < repeats; ++r) {
      const double ratio = time_at_error(curve(l.uniform, cost, r), e) /
                           time_at_error(curve(l.adaptive, cost, r), e);
      if (std::isfinite(ratio)) lo = std::min(lo, ratio), hi = std::max(hi, ratio);
    }
    std::printf("  relMSE %.5f: uniform %7.3f s, adaptive %7.3f s -> %5.2fx", e, tu, ta, tu / ta);
    if (repeats > 1 && lo <= hi) std::printf("  (single repeats %.2f-%.2fx)", lo, hi);
    std::printf("\n");
    log_sum += std::log(tu / ta);
  }
  return std::exp(log_sum / double(levels.size()));
}

// One scene: reference, ladders, tables. Returns the gain (NaN if skipped).
double run_case(const Case& c, const Settings& s) {
  const auto file = std::filesystem::path(VESPER_SOURCE_DIR) / "scenes" / c.name / "scene.json";
  std::optional<Scene> scene;
  try {
    SceneDescription desc = load_scene(file);
    desc.film.width = c.width;
    desc.film.height = c.height;
    scene = build_scene(desc);
  } catch (const std::exception& e) {
    std::printf("%s: skipped (%s)\n\n", c.name.c_str(), e.what());
    return NAN;
  }
  const int ref_spp = s.ref_spp.value_or(c.ref_spp);
  const Reference ref = load_or_render_reference(*scene, ref_spp, 7, s.cache);
  std::printf("%s (%dx%d, max_depth %d; reference %d spp, %s)\n", c.name.c_str(), c.width, c.height,
              scene->render.max_depth, ref_spp,
              ref.from_cache ? "from the cache"
                             : (std::to_string(ref.seconds).substr(0, 6) + " s").c_str());
  if (s.references_only) return NAN;
  measure(*scene, uniform_options(c.spp.front(), 1), ref);  // warm-up: threads, caches
  const std::vector<double> targets = calibrate_targets(c, *scene, ref, s);
  const Ladder l = measure_ladders(c, targets, *scene, ref, s);
  print_ladders(c, targets, l, ref);
  double smallest = INFINITY;
  for (const auto& rung : l.uniform) smallest = std::min(smallest, mean_of(rung).relmse);
  for (const auto& rung : l.adaptive) smallest = std::min(smallest, mean_of(rung).relmse);
  const std::vector<double> levels =
      common_error_levels(curve(l.uniform, Cost::Wall), curve(l.adaptive, Cost::Wall), 3);
  std::printf(
      "  reference noise floor %.2e = %.1f %% of the lowest relMSE compared (%.1f %% of the "
      "smallest measured)\n",
      ref.noise_floor, levels.empty() ? NAN : 100 * ref.noise_floor / levels.back(),
      100 * ref.noise_floor / smallest);
  const int mid_spp = c.spp[c.spp.size() / 2];
  const AllocationBounds b =
      allocation_bounds(ref.image, ref_spp, mid_spp, s.min_spp.value_or(kDefaultMinSpp));
  std::printf(
      "  ideal allocations at uniform %d spp's relMSE (reference variance, equal cost per "
      "sample):\n    threshold on max-channel sqrt(var)/(|m|+0.01) %.2fx, on relMSE's term %.2fx, "
      "Neyman %.2fx\n",
      mid_spp, b.threshold_max_channel, b.threshold_relmse, b.neyman);
  std::printf("  equal-error time uniform / adaptive, wall clock:\n");
  const double gain = print_equal_error(l, s.repeats, Cost::Wall);
  std::printf("  the same in process CPU time:\n");
  const double cpu_gain = print_equal_error(l, s.repeats, Cost::Cpu);
  std::printf("  equal-error gain (geometric mean over the levels): %.2fx wall, %.2fx CPU\n\n",
              gain, cpu_gain);
  return gain;
}

Settings parse(int argc, char** argv) {
  Settings s;
  s.quick = std::getenv("VESPER_BENCH_QUICK") != nullptr;
  s.cache = std::filesystem::temp_directory_path() / "vesper-bench-cache";
  if (const char* dir = std::getenv("VESPER_BENCH_CACHE")) s.cache = dir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--quick") {
      s.quick = true;
    } else if (a == "--references-only") {
      s.references_only = true;
    } else if (a == "--no-cache") {
      s.cache.reset();
    } else if (has_value && a == "--scene") {
      s.scenes.push_back(argv[++i]);
    } else if (has_value && a == "--repeats") {
      s.repeats = std::max(1, std::atoi(argv[++i]));
    } else if (has_value && a == "--cache") {
      s.cache = argv[++i];
    } else if (has_value && a == "--maps") {
      s.maps = argv[++i];
    } else if (has_value && a == "--ref-spp") {
      s.ref_spp = std::atoi(argv[++i]);
    } else if (has_value && a == "--min-spp") {
      s.min_spp = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "unknown argument %s (see the comment atop adaptive_gain.cpp)\n",
                   a.c_str());
      std::exit(2);
    }
  }
  if (s.quick) {
    s.repeats = 1;
    s.cache.reset();  // tiny references are cheaper to render than to keep
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each line as it comes, also into a file
  const Settings s = parse(argc, argv);
  std::vector<std::pair<std::string, double>> gains;
  for (const Case& c : cases(s.quick))
    if (s.scenes.empty() || std::find(s.scenes.begin(), s.scenes.end(), c.name) != s.scenes.end())
      gains.emplace_back(c.name, run_case(c, s));
  std::printf("equal-error time uniform / adaptive (> 1: adaptive is faster)\n");
  for (const auto& [name, gain] : gains)
    if (std::isfinite(gain)) std::printf("  %-12s %5.2fx\n", name.c_str(), gain);
  return 0;
}
