#include "measure/bench_runner.h"

#include <chrono>
#include <exception>

#include <fmt/format.h>

#include "measure/beauty.h"
#include "measure/noise_floor.h"
#include "measure/reference_cache.h"
#include "renderer/output/image_metrics.h"

namespace vesper::measure {
namespace {

struct SceneContext {
  const SceneResult* scene;
  BenchScene bench;
  std::string position;  // "scene 3/6"
};

void emit(const std::function<void(const std::string&)>& f, const std::string& s) {
  if (f) f(s);
}

RenderedImage timed_render(const BenchRenderer& r, const SceneContext& ctx, int spp, uint64_t seed,
                           const RunnerOptions& o, const RunnerEvents& ev,
                           const std::string& what) {
  emit(ev.render_begins, fmt::format("{} {}: {} {}", ctx.position, ctx.scene->name, r.name, what));
  struct End {
    const RunnerEvents& ev;
    ~End() {
      if (ev.render_ends) ev.render_ends();
    }
  } end{ev};
  RenderedImage img = r.render(ctx.bench, spp, seed, o.threads);
  img.image = beauty_rgb(img.image);
  if (img.image.width != ctx.bench.width || img.image.height != ctx.bench.height)
    throw std::runtime_error(fmt::format("{}: {} rendered {}x{}, expected {}x{}", r.name,
                                         ctx.scene->name, img.image.width, img.image.height,
                                         ctx.bench.width, ctx.bench.height));
  return img;
}

// The reference from the cache, or rendered as two halves and cached.
CachedReference reference_for(const BenchRenderer& r, const SceneContext& ctx,
                              const RunnerOptions& o, const RunnerEvents& ev, RendererRun& run) {
  const auto [seed_a, seed_b] = reference_seeds(o.seed);
  const SceneResult& s = *ctx.scene;
  const ReferenceKey key{s.name,  r.name,   r.cache_key,     s.scene_hash,
                         s.width, s.height, s.reference_spp, seed_a};
  run.reference_file = reference_path(o.refs_dir, key).string();
  std::string warning;
  if (auto cached = load_reference(o.refs_dir, key, &warning)) {
    run.reference_cached = true;
    return std::move(*cached);
  }
  if (!warning.empty()) emit(ev.warn, warning);
  const int half = s.reference_spp / 2;
  const RenderedImage a =
      timed_render(r, ctx, half, seed_a, o, ev, fmt::format("reference {} spp (half 1/2)", half));
  const RenderedImage b =
      timed_render(r, ctx, half, seed_b, o, ev, fmt::format("reference {} spp (half 2/2)", half));
  CachedReference ref;
  ref.image = mean_of_halves(a.image, b.image);
  ref.noise_floor = reference_noise_floor(a.image, b.image);
  ref.render_seconds = a.render_seconds + b.render_seconds;
  try {
    store_reference(o.refs_dir, key, ref);
  } catch (const std::exception& e) {  // the run can go on; the next one renders it again
    emit(ev.warn, fmt::format("could not cache the reference: {}", e.what()));
  }
  return ref;
}

// Fills run's reference fields and curve; returns the reference (for the peer comparison).
LayeredImage measure_renderer(const BenchRenderer& r, const SceneContext& ctx,
                              const RunnerOptions& o, const RunnerEvents& ev, RendererRun& run) {
  const CachedReference ref = reference_for(r, ctx, o, ev, run);
  run.noise_floor = ref.noise_floor;
  run.reference_seconds = ref.render_seconds;
  for (int spp : ctx.scene->spp_ladder) {
    const RenderedImage img = timed_render(r, ctx, spp, o.seed, o, ev, fmt::format("{} spp", spp));
    run.curve.push_back(
        {spp, img.render_seconds, img.wall_seconds, relative_mse(img.image, ref.image)});
  }
  return ref.image;
}

void fill_times(RendererRun& run, const std::vector<double>& targets) {
  std::vector<CurvePoint> curve;
  for (const Measurement& m : run.curve) curve.push_back({m.render_seconds, m.relmse});
  for (double t : targets) run.times.push_back({t, time_to_error(curve, t)});
}

bool exact(TimeEstimate e) { return e == TimeEstimate::Interpolated; }

PeerComparison compare_with_peer(const SceneResult& s, const RendererRun& vesper,
                                 const RendererRun& peer, const LayeredImage* vesper_ref,
                                 const LayeredImage* peer_ref) {
  PeerComparison c;
  c.peer = peer.renderer;
  if (vesper_ref && peer_ref) c.agreement = compare_references(*vesper_ref, *peer_ref);
  for (size_t i = 0; i < vesper.times.size() && i < peer.times.size(); ++i) {
    const TimeToError &tv = vesper.times[i].time, &tp = peer.times[i].time;
    RatioAtTarget r;
    r.target = vesper.times[i].target;
    r.goal = goal_ratio(s.kind);
    if (tv.estimate != TimeEstimate::None && tp.estimate != TimeEstimate::None) {
      r.ratio = tv.seconds / tp.seconds;
      r.approximate = !exact(tv.estimate) || !exact(tp.estimate);
      r.goal_met = *r.ratio <= r.goal;
    }
    c.ratios.push_back(r);
  }
  return c;
}

void run_scene(SceneResult& s, const std::string& position,
               const std::vector<BenchRenderer>& renderers, const RunnerOptions& o,
               const RunnerEvents& ev) {
  const SceneContext ctx{&s, BenchScene{s.name, s.scene_path, s.kind, s.width, s.height}, position};
  std::vector<std::optional<LayeredImage>> refs;
  for (const BenchRenderer& r : renderers) {
    RendererRun run;
    run.renderer = r.name;
    run.cache_key = r.cache_key;
    std::optional<LayeredImage> ref;
    try {
      ref = measure_renderer(r, ctx, o, ev, run);
    } catch (const std::exception& e) {
      run.error = e.what();
      emit(ev.warn, fmt::format("{} {}: {}", position, s.name, e.what()));
    }
    fill_times(run, o.targets);
    s.runs.push_back(std::move(run));
    refs.push_back(std::move(ref));
  }
  for (size_t p = 1; p < renderers.size(); ++p)
    s.comparisons.push_back(compare_with_peer(
        s, s.runs[0], s.runs[p], refs[0] ? &*refs[0] : nullptr, refs[p] ? &*refs[p] : nullptr));
}

}  // namespace

std::pair<uint64_t, uint64_t> reference_seeds(uint64_t seed) {
  // Offsets far from any seed a user would pick next (1, 2, 3, ...).
  return {seed + 0x5eed0001ull, seed + 0x5eed0002ull};
}

BenchReport run_bench(const BenchSet& set, const std::vector<BenchRenderer>& renderers,
                      const RunnerOptions& options, const RunnerEvents& events) {
  const auto t0 = std::chrono::steady_clock::now();
  BenchReport report;
  report.set_path = set.path.string();
  report.quick = options.quick;
  report.threads = options.threads;
  report.seed = options.seed;
  report.targets = options.targets;
  for (const BenchRenderer& r : renderers) report.renderers.push_back(r.name);
  report.scenes = prepare_scenes(set, options.quick);
  const size_t n = report.scenes.size();
  for (size_t i = 0; i < n; ++i) {
    SceneResult& s = report.scenes[i];
    const std::string position = fmt::format("scene {}/{}", i + 1, n);
    if (s.skipped) {
      emit(events.warn, fmt::format("{} {}: {}", position, s.name, s.note));
      continue;
    }
    run_scene(s, position, renderers, options, events);
  }
  report.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace vesper::measure
