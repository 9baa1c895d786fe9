#include "renderer/render/render.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "renderer/integrator/light_tracer.h"
#include "renderer/integrator/light_vertex.h"
#include "renderer/output/metadata_text.h"
#include "renderer/output/range_metadata.h"
#include "renderer/render/channel_layout.h"
#include "renderer/render/light_pass.h"
#include "renderer/render/photon_pass.h"
#include "renderer/render/pixel_sampler.h"
#include "renderer/render/sampling_plan.h"

namespace vesper {
namespace {

constexpr int kTileSize = 16;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

bool photon_merging_runs(const Scene& scene, const RenderOptions& options) {
  return options.photon_merging.value_or(scene.render.photon_merging) &&
         photon_merging_applies(scene);
}

// `photons`: photon_merging_runs, decided once per render.
PathTracerOptions path_tracer_options(const Scene& scene, const RenderOptions& options,
                                      const ChannelLayout& layout, const SamplingPlan& plan,
                                      bool photons) {
  PathTracerOptions pt;
  pt.max_depth = scene.render.max_depth;
  pt.want_aovs = layout.albedo >= 0 || layout.normal >= 0 || layout.depth >= 0;
  pt.equiangular = options.equiangular;
  pt.equiangular_in_cone = options.equiangular_in_cone;
  pt.sun_shafts = options.sun_shafts;
  pt.light_vertices = options.light_vertices.value_or(light_vertices_pay_off(scene));
  pt.want_camera_transmittance = layout.need_transmittance;
  const std::optional<double> clamp = options.clamp ? options.clamp : scene.render.clamp;
  pt.indirect_clamp = float(clamp.value_or(0.0));
  if (photons) {  // photons take light tracing's part of path space, in its place
    pt.light_traced_from = std::max(2, options.light_traced_from.value_or(kLightTracedFrom));
    pt.light_traced_all = light_tracing_takes_every_light(scene);
    return pt;
  }
  // Light tracing adds its splats to a fixed sample count per pixel: not
  // to adaptive renders, whose pixels stop at different counts. Nor with
  // the indirect clamp, which bounds each camera sample's indirect light:
  // splats would bypass it.
  const int from =
      options.light_traced_from.value_or(light_tracing_pays_off(scene) ? kLightTracedFrom : 0);
  if (from > 0 && light_tracing_applies(scene) && !plan.multipass() && !options.pixel_samples &&
      !(pt.indirect_clamp > 0.f)) {
    pt.light_traced_from = std::max(2, from);
    pt.light_traced_all = light_tracing_takes_every_light(scene);
  }
  return pt;
}

// One pass over the tiles: each pixel is brought to its target sample count.
struct Pass {
  const PixelSamplerContext& pixel;
  const PathTracerOptions& pt;
  int height = 0, tiles_x = 0, tiles_y = 0;
  // Film mode: the sums persist across passes (adaptive, time limit, partials).
  FilmSums* film = nullptr;
  // Local mode (one pass, no sums kept): each pixel is resolved into image right away.
  LayeredImage* image = nullptr;
  const std::vector<int64_t>* targets = nullptr;  // per pixel; null = uniform
  int64_t uniform_target = 0;
  const LightSplats* splats = nullptr;  // the light tracer's, added to every pixel

  int64_t target(size_t p) const { return targets ? (*targets)[p] : uniform_target; }
  size_t tiles() const { return size_t(tiles_x) * size_t(tiles_y); }
};

// Per-thread sums of one pixel in local mode.
struct ScratchPixel {
  std::vector<ExactSum> sums, stream_sums;
  std::vector<uint32_t> counts;
  ScratchPixel(size_t channels, size_t streamed)
      : sums(channels), stream_sums(size_t(kSampleStreams) * streamed), counts(kSampleStreams) {}
  PixelSums clear() {
    std::fill(sums.begin(), sums.end(), ExactSum(0));
    std::fill(stream_sums.begin(), stream_sums.end(), ExactSum(0));
    std::fill(counts.begin(), counts.end(), 0u);
    return {sums.data(), stream_sums.empty() ? nullptr : stream_sums.data(), counts.data()};
  }
};

SampleCounts render_tile(const Pass& pass, size_t tile) {
  set_flush_to_zero();
  const PixelSamplerContext& c = pass.pixel;
  const size_t nc = c.layout.names.size();
  const DerivedChannels derived = find_derived_channels(c.layout.names, c.layout.streamed);
  ScratchPixel scratch(nc, c.layout.streamed.size());
  PathRecord record(int(c.scene.group_names.size()));
  PathTracerOptions pt = pass.pt;
  if (!c.layout.bin_outputs.empty()) pt.record = &record;
  const int tx = int(tile % size_t(pass.tiles_x)), ty = int(tile / size_t(pass.tiles_x));
  SampleCounts counts;
  for (int y = ty * kTileSize; y < std::min(pass.height, (ty + 1) * kTileSize); ++y)
    for (int x = tx * kTileSize; x < std::min(c.width, (tx + 1) * kTileSize); ++x) {
      const size_t p = size_t(y) * size_t(c.width) + size_t(x);
      const int64_t target = pass.target(p);
      if (pass.film) {
        const PixelSums px = pass.film->pixel(p);
        counts += sample_pixel(c, x, y, sample_count(px.counts), target, pt, record, px);
        if (pass.splats) pass.splats->add_to(p, px);
      } else {
        const PixelSums px = scratch.clear();
        counts += sample_pixel(c, x, y, 0, target, pt, record, px);
        if (pass.splats) pass.splats->add_to(p, px);
        resolve_pixel({px.sums, px.stream_sums, px.counts, c.layout.streamed.size()}, nc, derived,
                      pass.image->pixels.data() + p * nc);
      }
    }
  return counts;
}

// All tiles over TBB (`threads`, 0 = all); `after_tile` is called after each.
template <typename AfterTile>
SampleCounts run_pass(const Pass& pass, int threads, AfterTile&& after_tile) {
  std::atomic<uint64_t> camera{0}, rays{0}, nonfinite{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pass.tiles(), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t t = r.begin(); t != r.end(); ++t) {
                          const SampleCounts n = render_tile(pass, t);
                          camera += n.camera_samples;
                          rays += n.rays;
                          nonfinite += n.nonfinite;
                          after_tile(n);
                        }
                      });
  });
  return {camera, rays, nonfinite};
}

// The next pass's per-pixel targets, or nothing when sampling is done (and why).
struct NextPass {
  std::vector<int64_t> targets;
  bool any = false;
};

NextPass plan_next_pass(const FilmSums& film, const SamplingPlan& plan, double elapsed,
                        double last_pass_seconds, uint64_t last_pass_samples, StopReason& why) {
  NextPass next;
  const std::vector<PixelState> state = pixel_states(film, plan.noise_target, plan.cap);
  next.targets.resize(film.pixel_count());
  uint64_t planned = 0;
  bool capped = false;
  for (size_t p = 0; p < state.size(); ++p) {
    const int64_t n = sample_count(film.pixel(p).counts);
    next.targets[p] = state[p] == PixelState::Active ? next_sample_count(n, plan.cap) : n;
    planned += uint64_t(next.targets[p] - n);
    capped |= state[p] == PixelState::Capped;
  }
  if (planned == 0) {
    why = !plan.noise_target ? StopReason::Spp
          : capped           ? StopReason::MaxSpp
                             : StopReason::NoiseTarget;
    return next;
  }
  if (plan.time_limit) {
    // Stop at the end of the pass in which the budget ran out, and shrink the
    // next pass so that it ends near the budget.
    const double left = *plan.time_limit - elapsed;
    if (left <= 0) {
      why = StopReason::TimeLimit;
      return next;
    }
    const double rate = double(last_pass_samples) / std::max(last_pass_seconds, 1e-6);
    const double fraction = left * rate / double(planned);
    if (fraction < 1)
      for (size_t p = 0; p < state.size(); ++p) {
        const int64_t n = sample_count(film.pixel(p).counts);
        const int64_t add = next.targets[p] - n;
        if (add > 0) next.targets[p] = n + std::max<int64_t>(1, int64_t(double(add) * fraction));
      }
  }
  next.any = true;
  return next;
}

// Adaptive or time-limited sampling: passes over the film until plan_next_pass says stop.
template <typename AfterTile>
SampleCounts run_passes(Pass& pass, const SamplingPlan& plan, int threads, Clock::time_point t0,
                        RenderStats& stats, AfterTile&& after_tile) {
  SampleCounts total;
  pass.uniform_target = plan.first_pass;
  NextPass next;
  for (stats.sampling_passes = 1;; ++stats.sampling_passes) {
    const auto pass_start = Clock::now();
    const SampleCounts n = run_pass(pass, threads, after_tile);
    total += n;
    next = plan_next_pass(*pass.film, plan, seconds_since(t0), seconds_since(pass_start),
                          n.camera_samples, stats.stop_reason);
    if (!next.any) break;
    pass.targets = &next.targets;
  }
  return total;
}

// The image's channels: the layout's, plus variance and spp when adaptive.
std::vector<Aov> requested_aovs(const Scene& scene, const RenderOptions& options,
                                const SamplingPlan& plan) {
  std::vector<Aov> aovs = options.aovs ? *options.aovs : scene.render.aovs;
  if (options.layer_variance && std::find(aovs.begin(), aovs.end(), Aov::Variance) == aovs.end())
    aovs.push_back(Aov::Variance);
  if (plan.noise_target)
    for (Aov a : {Aov::Variance, Aov::Spp})
      if (std::find(aovs.begin(), aovs.end(), a) == aovs.end()) aovs.push_back(a);
  return aovs;
}

void check_pixel_samples(const RenderOptions& options, const SamplingPlan& plan, size_t pixels) {
  if (!options.pixel_samples) return;
  if (options.pixel_samples->size() != pixels)
    throw std::invalid_argument("render: pixel_samples has " +
                                std::to_string(options.pixel_samples->size()) + " counts for " +
                                std::to_string(pixels) + " pixels");
  for (int64_t n : *options.pixel_samples)
    if (n < 0 || n > plan.cap)
      throw std::invalid_argument("render: a pixel sample count " + std::to_string(n) +
                                  " is outside the range of " + std::to_string(plan.cap));
}

void set_sampling_metadata(std::map<std::string, std::string>& meta, const SamplingPlan& plan,
                           const RenderStats& stats, const FilmSums& film) {
  namespace key = metadata_key;
  if (plan.noise_target) meta[key::kNoiseTarget] = metadata_number(*plan.noise_target);
  if (plan.time_limit) meta[key::kTimeLimit] = metadata_number(*plan.time_limit);
  if (!plan.multipass()) return;
  meta[key::kStopReason] = stop_reason_name(stats.stop_reason);
  meta[key::kSamplingPasses] = std::to_string(stats.sampling_passes);
  set_noise_metadata(meta, film);
}

// The shutter (and motion steps) the image was exposed over.
void set_shutter_metadata(std::map<std::string, std::string>& meta, const Scene& scene) {
  if (!scene.render.shutter) return;
  meta[metadata_key::kShutter] =
      fmt::format("{} {}", scene.render.shutter->open, scene.render.shutter->close);
  if (scene.motion_blur) meta[metadata_key::kMotionSteps] = std::to_string(scene.motion_steps);
}

}  // namespace

const char* stop_reason_name(StopReason r) {
  switch (r) {
    case StopReason::Spp:
      return "spp";
    case StopReason::NoiseTarget:
      return "noise_target";
    case StopReason::MaxSpp:
      return "max_spp";
    case StopReason::TimeLimit:
      return "time_limit";
  }
  return "spp";
}

// The passes before the camera pass: light tracing's splats or photon
// merging's photons (at most one of them).
struct LightPasses {
  std::optional<PhotonPassResult> photons;
  std::optional<LightSplats> splats;
  uint64_t rays() const { return (splats ? splats->rays() : 0) + (photons ? photons->rays : 0); }
  uint64_t nonfinite() const {
    return (splats ? splats->nonfinite() : 0) + (photons ? photons->nonfinite : 0);
  }
};

// The light subpaths run_light_passes traces (progress).
uint64_t light_subpaths(const Scene& scene, const RenderOptions& options,
                        const PathTracerOptions& pt, uint64_t camera_most, bool photons) {
  if (photons) return photon_subpaths(scene, frame_spp(scene.render, options));
  return pt.light_traced_from > 0 ? camera_most : 0;
}

// Traces the photons (pt.photons points at them) or the light tracer's splats.
void run_light_passes(LightPasses& light, const Scene& scene, const RenderOptions& options,
                      const ChannelLayout& layout, const SamplingPlan& plan, PathTracerOptions& pt,
                      bool photons, const std::function<void(uint64_t)>& report) {
  if (photons) {
    const std::optional<double> radius =
        options.photon_radius ? options.photon_radius : scene.render.photon_radius;
    // Scene units to render space (scene.h).
    light.photons =
        trace_photons(scene, pt, plan.seed, frame_spp(scene.render, options),
                      float(radius.value_or(0.0) / scene.unit_scale), options.threads, report);
    pt.photons = &light.photons->photons;
  } else if (pt.light_traced_from > 0) {
    light.splats.emplace(scene, pt, layout, plan, options.threads, report);
  }
}

// The biased estimators that ran, and what sets their bias: the image says so.
void set_bias_metadata(std::map<std::string, std::string>& metadata, const Scene& scene,
                       const PathTracerOptions& pt, const LightPasses& light) {
  if (pt.indirect_clamp > 0.f)
    metadata[metadata_key::kClamp] = fmt::format("{}", pt.indirect_clamp);
  if (light.photons)
    metadata[metadata_key::kPhotonMerging] =
        fmt::format("radius {:.4g} photons {} subpaths {}",
                    double(light.photons->photons.map.radius()) * scene.unit_scale,
                    light.photons->photons.map.size(), light.photons->photons.subpaths);
}

RenderResult render(const Scene& scene, const RenderOptions& options) {
  const auto t0 = Clock::now();
  const SamplingPlan plan = plan_sampling(scene.render, options);
  const ChannelLayout layout = layout_for(scene, requested_aovs(scene, options, plan),
                                          options.layers, options.layer_variance);
  const bool photons = photon_merging_runs(scene, options);
  PathTracerOptions pt = path_tracer_options(scene, options, layout, plan, photons);

  RenderResult out;
  LayeredImage& img = out.image;
  img.width = scene.film.width;
  img.height = scene.film.height;
  img.channels = layout.names;
  const size_t pixels = size_t(img.width) * size_t(img.height);
  check_pixel_samples(options, plan, pixels);

  std::optional<CryptoCounts> crypto;
  if (layout.cryptomatte) crypto.emplace(pixels);
  const PixelSamplerContext pixel{scene,      layout,    plan.seed,
                                  plan.begin, img.width, crypto ? &*crypto : nullptr};
  Pass pass{pixel, pt, img.height, (img.width + kTileSize - 1) / kTileSize,
            (img.height + kTileSize - 1) / kTileSize};
  pass.targets = options.pixel_samples;
  pass.uniform_target = plan.cap;
  // Progress in camera samples, against the most the range allows, after
  // the light subpaths of light tracing or photon merging.
  const uint64_t camera_most = uint64_t(pixels) * uint64_t(plan.cap);
  const uint64_t most = camera_most + light_subpaths(scene, options, pt, camera_most, photons);
  std::atomic<uint64_t> done{0};
  auto report = [&](uint64_t n) {
    const uint64_t d = done += n;
    if (options.on_progress) options.on_progress(size_t(std::min(d, most)), size_t(most));
  };
  LightPasses light;
  run_light_passes(light, scene, options, layout, plan, pt, photons, report);
  pass.splats = light.splats ? &*light.splats : nullptr;
  auto after_tile = [&](const SampleCounts& n) { report(n.camera_samples); };

  SampleCounts counts;
  if (!options.keep_sums && !plan.multipass()) {
    img.pixels.assign(pixels * layout.names.size(), 0.f);
    pass.image = &img;
    counts = run_pass(pass, options.threads, after_tile);
  } else {
    out.film = FilmSums(img.width, img.height, layout.names, layout.streamed);
    pass.film = &out.film;
    counts = plan.multipass() && !options.pixel_samples
                 ? run_passes(pass, plan, options.threads, t0, out.stats, after_tile)
                 : run_pass(pass, options.threads, after_tile);
    img.pixels = resolve_image(out.film).pixels;
  }
  if (options.on_progress) options.on_progress(size_t(most), size_t(most));
  if (crypto) {
    CryptoFilm film = append_cryptomatte(img, scene, *crypto, options.cryptomatte_depth);
    if (options.keep_sums) out.crypto = std::move(film);
  }

  out.stats.seconds = seconds_since(t0);
  out.stats.camera_samples = counts.camera_samples;
  out.stats.rays = counts.rays + light.rays();
  out.stats.nonfinite_samples = counts.nonfinite + light.nonfinite();
  set_range_metadata(img.metadata, {.scene_hash = scene.content_hash,
                                    .renderer_version = VESPER_VERSION,
                                    .spp = plan.cap,
                                    .sample_begin = plan.begin,
                                    .sample_end = plan.end,
                                    .seed = plan.seed,
                                    .render_seconds = out.stats.seconds,
                                    .nonfinite_samples = out.stats.nonfinite_samples});
  set_sampling_metadata(img.metadata, plan, out.stats, out.film);
  set_bias_metadata(img.metadata, scene, pt, light);
  set_shutter_metadata(img.metadata, scene);
  if (!options.keep_sums) out.film = FilmSums();
  return out;
}

}  // namespace vesper
