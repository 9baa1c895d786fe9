#include <spdlog/spdlog.h>
#include <algorithm>
#include <cmath>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/frame_output.h"
#include "cli/parent_watch.h"
#include "cli/progress.h"
#include "common/frame_pattern.h"
#include "jobs/frame_range.h"
#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_keys.h"
#include "renderer/output/partial_io.h"
#include "renderer/render/frame.h"
#include "renderer/sampling/random_hash.h"
#include "renderer/scene/aov_names.h"
#include "renderer/scene/scene_loader.h"

namespace vesper::cli {
namespace {

using Clock = std::chrono::steady_clock;

std::vector<Aov> parse_aovs(const std::string& list) {
  std::vector<Aov> aovs;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, end - start);
    const std::optional<Aov> a = aov_from_name(name);
    if (!a) {
      std::string known;
      for (const auto n : kAovNames) known += (known.empty() ? "" : ", ") + std::string(n);
      throw std::invalid_argument("--aov: unknown AOV '" + name + "' (expected one of: " + known +
                                  ")");
    }
    if (std::find(aovs.begin(), aovs.end(), *a) == aovs.end()) aovs.push_back(*a);
    start = end + 1;
  }
  return aovs;
}

// The sample range [begin, end) this run renders, checked; nullopt after
// logging the problem (a usage error).
std::optional<std::pair<int, int>> sample_range(const RenderCommandOptions& o, int spp) {
  const int begin = o.sample_begin, end = o.sample_end.value_or(spp);
  if (begin < 0 || end < begin) {
    spdlog::error("--samples: expected 0 <= begin <= end, got [{}, {})", begin, end);
    return std::nullopt;
  }
  if (int64_t(end) - begin > kMaxExactSamples) {
    spdlog::error(
        "--samples: [{}, {}) is more than {} samples per pixel; split it into ranges "
        "(--sample-begin/--sample-end --partial) and merge them",
        begin, end, kMaxExactSamples);
    return std::nullopt;
  }
  if (o.partial && end == begin) {
    spdlog::error("--partial: the sample range [{}, {}) is empty", begin, begin);
    return std::nullopt;
  }
  return std::pair{begin, end};
}

// --scale: the film's size times `scale`, at least 1x1 and at most 65536 a side.
void scale_film(FilmDesc& film, double scale) {
  auto scaled = [&](int n) { return int(std::clamp(std::lround(double(n) * scale), 1L, 65536L)); };
  film.width = scaled(film.width);
  film.height = scaled(film.height);
}

// How adaptive or time-limited sampling ended (nothing for plain renders).
void log_sampling(const std::map<std::string, std::string>& meta) {
  namespace key = metadata_key;
  if (!meta.count(key::kStopReason)) return;
  spdlog::info("sampling stopped by {} after {} passes: {} spp on average, noise {}",
               meta.at(key::kStopReason), meta.at(key::kSamplingPasses), meta.at(key::kSppMean),
               meta.count(key::kNoiseReached) ? meta.at(key::kNoiseReached) : "not measured");
}

// One frame (or the scene without a frame): what `vesper render` did before --frames.
// The frame as a partial render: its exact sums and, with Cryptomatte, its counts by id.
void write_partial_frame(FrameResult& frame, int spp, const std::filesystem::path& path) {
  write_partial(
      make_partial(frame.image, std::move(frame.film), spp, path.string(), std::move(frame.crypto)),
      path);
}

// What the flags override (the seed becomes the frame's with --frame).
void set_flag_options(const RenderCommandOptions& o, const SceneDescription& desc,
                      RenderOptions& ro) {
  ro.spp = o.spp;
  ro.seed = o.seed;
  if (o.frame) ro.seed = frame_seed(o.seed.value_or(desc.render.seed), *o.frame);
  if (o.threads) ro.threads = *o.threads;
  ro.sample_begin = o.sample_begin;
  ro.sample_end = o.sample_end;
  ro.keep_sums = o.partial;
  ro.noise_target = o.sampling.noise_target;
  ro.time_limit = o.sampling.time_limit;
  ro.min_spp = o.sampling.min_spp;
  ro.max_spp = o.sampling.max_spp;
  ro.layer_variance = o.layer_variance;
  ro.clamp = o.clamp;
  if (o.photon_merging) ro.photon_merging = true;
  ro.photon_radius = o.photon_radius;
}

int render_one(const RenderCommandOptions& o) {
  RenderOptions ro;
  SceneDescription desc;
  std::unique_ptr<FrameOutput> output;
  std::filesystem::path out_path;
  try {  // every usage error before any work: flags, scene, output path
    if (o.aovs) ro.aovs = parse_aovs(*o.aovs);
    SceneLoadOptions load{.scene_dir_only = o.scene_dir_only};
    if (o.frame) load.frame = double(*o.frame);
    desc = load_scene(o.scene, load);
    if (o.scale) scale_film(desc.film, *o.scale);
    if (o.half) desc.film.pixel_type = ExrPixelType::Half;
    output = std::make_unique<FrameOutput>(o.output, o.partial);
    out_path = output->path(o.frame ? std::optional<long>(*o.frame) : std::nullopt);
  } catch (const std::invalid_argument& e) {  // --aov
    spdlog::error("{}", e.what());
    return 2;
  } catch (const SceneError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const OutputError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  set_flag_options(o, desc, ro);
  try {
    check_sampling_options(desc.render, ro);
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}: {}", o.scene, e.what());
    return 2;
  }
  const int spp = frame_spp(desc.render, ro);
  const auto range = sample_range(o, spp);
  if (!range) return 2;

  if (!o.quiet)
    spdlog::info("{}: {}x{}, {}{} spp, {} shapes, {} lights, {} media, {} layers", o.scene,
                 desc.film.width, desc.film.height,
                 ro.noise_target || desc.render.noise_target ? "up to " : "",
                 range->second - range->first, desc.shapes.size(), desc.lights.size(),
                 desc.media.size(), desc.layers.size());
  Progress progress("render");
  if (!o.quiet) ro.on_progress = [&](size_t d, size_t t) { progress.update(d, t); };
  FrameResult result = render_frame(desc, ro);
  progress.finish();
  if (o.frame) result.image.metadata[metadata_key::kFrame] = std::to_string(*o.frame);

  try {
    if (o.partial)
      write_partial_frame(result, spp, out_path);
    else
      output->write(result.image, out_path);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  const double mrays = double(result.stats.rays) / result.stats.seconds * 1e-6;
  if (result.stats.nonfinite_samples > 0)
    spdlog::warn("{} non-finite samples were caught and dropped", result.stats.nonfinite_samples);
  if (!o.quiet)
    spdlog::info("wrote {} ({:.2f} s, {:.1f} Mrays/s)", out_path.string(), result.stats.seconds,
                 mrays);
  if (!o.quiet) log_sampling(result.image.metadata);
  std::printf("%s\n", out_path.string().c_str());
  std::fflush(stdout);  // a line per frame as it is written (--frames)
  return 0;
}

// --frames: each frame as `vesper render --frame N` renders it, in order. A
// frame that fails stops the run naming it; the frames written before stay.
int render_frames(const RenderCommandOptions& o) {
  std::vector<int> frames;
  try {
    frames = parse_frame_range(*o.frames);
    if (frames.size() > 1 && !has_frame_pattern(o.output))
      throw OutputError(o.output + ": " + std::to_string(frames.size()) +
                        " frames need a frame pattern ('#') in the output name, e.g. shot.####" +
                        std::filesystem::path(o.output).extension().string());
    FrameOutput(o.output, o.partial);  // a bad -o fails before the first frame
  } catch (const FrameRangeError& e) {
    spdlog::error("--frames: {}", e.what());
    return 2;
  } catch (const OutputError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  const Clock::time_point start = Clock::now();
  for (size_t i = 0; i < frames.size(); ++i) {
    RenderCommandOptions one = o;
    one.frames.reset();
    one.frame = frames[i];
    if (const int rc = render_one(one); rc != 0) {
      const std::string written = i == 0   ? "no frame was written"
                                  : i == 1 ? "the frame before it is written"
                                           : fmt::format("the {} frames before it are written", i);
      spdlog::error("frame {} ({} of {}) failed; {}", frames[i], i + 1, frames.size(), written);
      return rc;
    }
    if (!o.quiet)
      spdlog::info("frame {} done ({} of {}, {:.1f} s so far)", frames[i], i + 1, frames.size(),
                   std::chrono::duration<double>(Clock::now() - start).count());
  }
  return 0;
}

}  // namespace

int run_render(const RenderCommandOptions& o) {
  if (!die_with_parent()) return 1;
  return o.frames ? render_frames(o) : render_one(o);
}

}  // namespace vesper::cli
