#include "renderer/render/render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "renderer/integrator/path_tracer.h"
#include "renderer/output/range_metadata.h"
#include "renderer/render/channel_layout.h"
#include "renderer/sampling/pixel_filter.h"

namespace vesper {
namespace {

constexpr int kTileSize = 16;

// Samples [begin, end) of every pixel; a pixel's samples depend only on
// (seed, pixel, sample index).
struct SampleRange {
  int begin = 0, end = 0;
  int count = 0;  // max(0, end - begin): the divisor of every pixel mean
  uint64_t seed = 0;
};

SampleRange sample_range(const Scene& scene, const RenderOptions& options) {
  SampleRange r;
  r.begin = options.sample_begin;
  r.end = options.sample_end.value_or(options.spp.value_or(scene.render.spp));
  r.count = std::max(0, r.end - r.begin);
  r.seed = options.seed.value_or(scene.render.seed);
  if (r.count > kMaxExactSamples)
    throw std::invalid_argument(
        "render: " + std::to_string(r.count) + " samples per pixel in one range; at most " +
        std::to_string(kMaxExactSamples) + " fit the exact sample sums (split the range)");
  return r;
}

PathTracerOptions path_tracer_options(const Scene& scene, const RenderOptions& options,
                                      const ChannelLayout& layout) {
  PathTracerOptions pt;
  pt.max_depth = scene.render.max_depth;
  pt.want_aovs = layout.albedo >= 0 || layout.normal >= 0 || layout.depth >= 0;
  pt.equiangular = options.equiangular;
  pt.want_camera_transmittance = layout.need_transmittance;
  return pt;
}

// What every tile of one render shares.
struct TileContext {
  const Scene& scene;
  const ChannelLayout& layout;
  const PathTracerOptions& pt;
  SampleRange range;
  int tiles_x = 0;
  LayeredImage& image;
  std::vector<ExactSum>* sums;  // null unless RenderOptions::keep_sums
};

struct TileCounts {
  uint64_t rays = 0, nonfinite = 0;
};

// Adds one camera sample's values to the pixel's sums. A non-finite radiance
// would poison the whole pixel: it is dropped, and false returned so that it is counted.
bool accumulate(std::vector<ExactSum>& acc, const PathResult& r, const PathRecord& record,
                const ChannelLayout& layout) {
  const bool finite = r.radiance.is_finite();
  if (finite) {
    acc[0] += to_fixed(r.radiance.r);
    acc[1] += to_fixed(r.radiance.g);
    acc[2] += to_fixed(r.radiance.b);
    for (const BinOutput& o : layout.bin_outputs) {
      Rgb sum;
      for (size_t b : o.bins) sum += record.bins()[b];
      for (int c = 0; c < 3; ++c) acc[size_t(o.channel + c)] += to_fixed(sum[c]);
    }
  }
  acc[3] += to_fixed(r.alpha);
  for (const BinOutput& o : layout.bin_outputs)
    if (o.alpha_channel >= 0 && std::isfinite(r.camera_transmittance))
      acc[size_t(o.alpha_channel)] += to_fixed(float(1.0 - r.camera_transmittance));
  if (layout.albedo >= 0 && r.albedo.is_finite())
    for (int c = 0; c < 3; ++c) acc[size_t(layout.albedo + c)] += to_fixed(r.albedo[c]);
  if (layout.normal >= 0 && is_finite(r.normal))
    for (int c = 0; c < 3; ++c) acc[size_t(layout.normal + c)] += to_fixed(r.normal[c]);
  if (layout.depth >= 0 && std::isfinite(r.depth)) acc[size_t(layout.depth)] += to_fixed(r.depth);
  return finite;
}

// Every sample of pixel (x, y) into `acc`, then the pixel's means (and sums) into the output.
void render_pixel(const TileContext& c, int x, int y, const PathTracerOptions& pt,
                  const PathRecord& record, std::vector<ExactSum>& acc, TileCounts& counts) {
  std::fill(acc.begin(), acc.end(), ExactSum(0));
  const uint64_t pixel_index = uint64_t(y) * uint64_t(c.image.width) + uint64_t(x);
  for (int s = c.range.begin; s < c.range.end; ++s) {
    Sampler sampler(c.range.seed, pixel_index, uint64_t(s));
    const Vec2 offset = sample_pixel_filter(c.scene.film.filter, sampler.next2());
    const Vec2 u_lens = sampler.next2();
    const Ray ray =
        c.scene.camera.generate_ray(float(x) + 0.5f + offset.x, float(y) + 0.5f + offset.y, u_lens);
    const PathResult r = trace_path(c.scene, ray, sampler, pt);
    counts.rays += r.rays;
    if (!accumulate(acc, r, record, c.layout)) ++counts.nonfinite;
  }
  const size_t base = size_t(pixel_index) * acc.size();
  for (size_t k = 0; k < acc.size(); ++k)
    c.image.pixels[base + k] = exact_mean(acc[k], c.range.count);
  if (c.sums) std::copy(acc.begin(), acc.end(), c.sums->begin() + ptrdiff_t(base));
}

TileCounts render_tile(const TileContext& c, size_t tile) {
  set_flush_to_zero();
  const int tx = int(tile % size_t(c.tiles_x)), ty = int(tile / size_t(c.tiles_x));
  TileCounts counts;
  std::vector<ExactSum> acc(c.layout.names.size());
  PathRecord record(int(c.scene.group_names.size()));
  PathTracerOptions pt = c.pt;
  if (!c.layout.bin_outputs.empty()) pt.record = &record;
  const int w = c.image.width, h = c.image.height;
  for (int y = ty * kTileSize; y < std::min(h, (ty + 1) * kTileSize); ++y)
    for (int x = tx * kTileSize; x < std::min(w, (tx + 1) * kTileSize); ++x)
      render_pixel(c, x, y, pt, record, acc, counts);
  return counts;
}

// All tiles over TBB (options.threads, 0 = all), reporting progress after each.
TileCounts render_tiles(const TileContext& c, const RenderOptions& options) {
  const int tiles_y = (c.image.height + kTileSize - 1) / kTileSize;
  const size_t tiles_total = size_t(c.tiles_x) * size_t(tiles_y);
  std::atomic<size_t> tiles_done{0};
  std::atomic<uint64_t> rays{0}, nonfinite{0};
  const int threads =
      options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles_total, 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t t = r.begin(); t != r.end(); ++t) {
                          const TileCounts n = render_tile(c, t);
                          rays += n.rays;
                          nonfinite += n.nonfinite;
                          const size_t done = ++tiles_done;
                          if (options.on_progress) options.on_progress(done, tiles_total);
                        }
                      });
  });
  return {rays, nonfinite};
}

}  // namespace

RenderResult render(const Scene& scene, const RenderOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const SampleRange range = sample_range(scene, options);
  const std::vector<Aov>& aovs = options.aovs ? *options.aovs : scene.render.aovs;
  const ChannelLayout layout = layout_for(scene, aovs, options.layers);
  const PathTracerOptions pt = path_tracer_options(scene, options, layout);

  RenderResult out;
  LayeredImage& img = out.image;
  img.width = scene.film.width;
  img.height = scene.film.height;
  img.channels = layout.names;
  img.pixels.assign(size_t(img.width) * size_t(img.height) * layout.names.size(), 0.f);
  if (options.keep_sums) out.sums.assign(img.pixels.size(), 0);

  const TileContext context{scene,
                            layout,
                            pt,
                            range,
                            (img.width + kTileSize - 1) / kTileSize,
                            img,
                            options.keep_sums ? &out.sums : nullptr};
  const TileCounts counts = render_tiles(context, options);

  out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.stats.camera_samples = uint64_t(img.width) * uint64_t(img.height) * uint64_t(range.count);
  out.stats.rays = counts.rays;
  out.stats.nonfinite_samples = counts.nonfinite;
  set_range_metadata(img.metadata, {.scene_hash = scene.content_hash,
                                    .renderer_version = VESPER_VERSION,
                                    .spp = range.count,
                                    .sample_begin = range.begin,
                                    .sample_end = range.end,
                                    .seed = range.seed,
                                    .render_seconds = out.stats.seconds,
                                    .nonfinite_samples = out.stats.nonfinite_samples});
  return out;
}

}  // namespace vesper
