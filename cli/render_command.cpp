#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/parent_watch.h"
#include "cli/progress.h"
#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_keys.h"
#include "renderer/output/partial_io.h"
#include "renderer/render/frame.h"
#include "renderer/sampling/sampler.h"
#include "renderer/scene/aov_names.h"
#include "renderer/scene/scene_loader.h"

namespace vesper::cli {
namespace {

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

}  // namespace

int run_render(const RenderCommandOptions& o) {
  if (!die_with_parent()) return 1;
  RenderOptions ro;
  try {
    if (o.aovs) ro.aovs = parse_aovs(*o.aovs);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  SceneDescription desc;
  try {
    desc = load_scene(o.scene);
  } catch (const SceneError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  const std::filesystem::path out_path(o.output);
  if (out_path.has_parent_path() && !std::filesystem::is_directory(out_path.parent_path())) {
    spdlog::error("{}: output directory does not exist", out_path.parent_path().string());
    return 2;
  }
  ro.spp = o.spp;
  ro.seed = o.seed;
  if (o.frame) ro.seed = frame_seed(o.seed.value_or(desc.render.seed), *o.frame);
  if (o.threads) ro.threads = *o.threads;
  ro.sample_begin = o.sample_begin;
  ro.sample_end = o.sample_end;
  ro.keep_sums = o.partial;
  const int spp = o.spp.value_or(desc.render.spp);
  if (ro.sample_begin < 0 || ro.sample_end.value_or(spp) < ro.sample_begin) {
    spdlog::error("--samples: expected 0 <= begin <= end, got [{}, {})", ro.sample_begin,
                  ro.sample_end.value_or(spp));
    return 2;
  }
  if (int64_t(ro.sample_end.value_or(spp)) - ro.sample_begin > kMaxExactSamples) {
    spdlog::error(
        "--samples: [{}, {}) is more than {} samples per pixel; split it into ranges "
        "(--sample-begin/--sample-end --partial) and merge them",
        ro.sample_begin, ro.sample_end.value_or(spp), kMaxExactSamples);
    return 2;
  }
  if (o.partial && ro.sample_end.value_or(spp) == ro.sample_begin) {
    spdlog::error("--partial: the sample range [{}, {}) is empty", ro.sample_begin,
                  ro.sample_begin);
    return 2;
  }

  if (!o.quiet)
    spdlog::info("{}: {}x{}, {} spp, {} shapes, {} lights, {} media, {} layers", o.scene,
                 desc.film.width, desc.film.height, ro.sample_end.value_or(spp) - ro.sample_begin,
                 desc.shapes.size(), desc.lights.size(), desc.media.size(), desc.layers.size());
  Progress progress("render");
  if (!o.quiet) ro.on_progress = [&](size_t d, size_t t) { progress.update(d, t); };
  FrameResult result = render_frame(desc, ro);
  progress.finish();
  if (o.frame) result.image.metadata[metadata_key::kFrame] = std::to_string(*o.frame);

  try {
    if (o.partial)
      write_partial(make_partial(result.image, std::move(result.sums), spp, out_path.string()),
                    out_path);
    else
      write_exr(result.image, out_path);
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
  std::printf("%s\n", out_path.string().c_str());
  return 0;
}

}  // namespace vesper::cli
