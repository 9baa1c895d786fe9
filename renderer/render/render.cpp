#include "renderer/render/render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>

#include "renderer/integrator/path_tracer.h"
#include "renderer/sampling/pixel_filter.h"

namespace vesper {
namespace {

constexpr int kTileSize = 16;

// An RGB output made of path-record bins (layers and transport AOVs).
struct BinOutput {
  int channel = 0;  // first of R, G, B
  int alpha_channel = -1;
  std::vector<size_t> bins;
};

struct ChannelLayout {
  int albedo = -1, normal = -1, depth = -1;
  std::vector<BinOutput> bin_outputs;
  bool need_transmittance = false;
  std::vector<std::string> names{"R", "G", "B", "A"};

  int add_rgb(const std::string& prefix) {
    const int at = int(names.size());
    names.insert(names.end(), {prefix + ".R", prefix + ".G", prefix + ".B"});
    return at;
  }
};

std::vector<size_t> bins_for(std::initializer_list<FirstEvent> kinds,
                             std::initializer_list<bool> indirect, const std::vector<int>& groups,
                             int group_count) {
  std::vector<size_t> out;
  for (FirstEvent k : kinds)
    for (bool ind : indirect)
      for (int g : groups) out.push_back(PathRecord::bin(k, ind, g, group_count));
  return out;
}

ChannelLayout layout_for(const Scene& scene, const std::vector<Aov>& aovs,
                         const std::vector<LayerSelection>& layers) {
  using FE = FirstEvent;
  ChannelLayout l;
  const int groups = int(scene.group_names.size());
  std::vector<int> all_groups(static_cast<size_t>(groups));
  for (int g = 0; g < groups; ++g) all_groups[size_t(g)] = g;
  for (Aov a : aovs) {
    auto transport = [&](const char* name, std::initializer_list<FE> kinds,
                         std::initializer_list<bool> ind) {
      l.bin_outputs.push_back({l.add_rgb(name), -1, bins_for(kinds, ind, all_groups, groups)});
    };
    switch (a) {
      case Aov::Albedo:
        l.albedo = l.add_rgb("albedo");
        break;
      case Aov::Normal:
        l.normal = int(l.names.size());
        l.names.insert(l.names.end(), {"normal.X", "normal.Y", "normal.Z"});
        break;
      case Aov::Depth:
        l.depth = int(l.names.size());
        l.names.push_back("depth.Z");
        break;
      case Aov::Emission:
        transport("emission", {FE::SurfaceView, FE::VolumeView}, {false});
        break;
      case Aov::DiffuseDirect:
        transport("diffuse_direct", {FE::Diffuse}, {false});
        break;
      case Aov::DiffuseIndirect:
        transport("diffuse_indirect", {FE::Diffuse}, {true});
        break;
      case Aov::SpecularDirect:
        transport("specular_direct", {FE::Specular}, {false});
        break;
      case Aov::SpecularIndirect:
        transport("specular_indirect", {FE::Specular}, {true});
        break;
      case Aov::VolumeDirect:
        transport("volume_direct", {FE::Volume}, {false});
        break;
      case Aov::VolumeIndirect:
        transport("volume_indirect", {FE::Volume}, {true});
        break;
    }
  }
  for (const LayerSelection& layer : layers) {
    std::vector<int> groups_kept;
    if (!layer.lights) {
      groups_kept = all_groups;
    } else {
      for (const std::string& name : *layer.lights) {
        const auto it = std::find(scene.group_names.begin(), scene.group_names.end(), name);
        if (it != scene.group_names.end())
          groups_kept.push_back(int(it - scene.group_names.begin()));
      }
    }
    std::vector<size_t> bins;
    switch (layer.paths) {
      case PathSelection::All:
        bins = bins_for({FE::SurfaceView, FE::VolumeView, FE::Diffuse, FE::Specular, FE::Volume},
                        {false, true}, groups_kept, groups);
        break;
      case PathSelection::Surface:
        bins = bins_for({FE::SurfaceView, FE::Diffuse, FE::Specular}, {false, true}, groups_kept,
                        groups);
        break;
      case PathSelection::Volume:
        bins = bins_for({FE::VolumeView, FE::Volume}, {false, true}, groups_kept, groups);
        break;
    }
    BinOutput out{l.add_rgb(layer.name), -1, std::move(bins)};
    if (layer.alpha) {
      out.alpha_channel = int(l.names.size());
      l.names.push_back(layer.name + ".A");
      l.need_transmittance = true;
    }
    l.bin_outputs.push_back(std::move(out));
  }
  return l;
}

}  // namespace

RenderResult render(const Scene& scene, const RenderOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const int width = scene.film.width, height = scene.film.height;
  const int spp = options.spp.value_or(scene.render.spp);
  const int sample_begin = options.sample_begin;
  const int sample_end = options.sample_end.value_or(spp);
  const uint64_t seed = options.seed.value_or(scene.render.seed);
  const std::vector<Aov>& aovs = options.aovs ? *options.aovs : scene.render.aovs;
  const ChannelLayout layout = layout_for(scene, aovs, options.layers);
  const size_t nch = layout.names.size();
  const bool want_record = !layout.bin_outputs.empty();

  RenderResult out;
  LayeredImage& img = out.image;
  img.width = width;
  img.height = height;
  img.channels = layout.names;
  img.pixels.assign(size_t(width) * size_t(height) * nch, 0.f);

  PathTracerOptions pt;
  pt.max_depth = scene.render.max_depth;
  pt.want_aovs = layout.albedo >= 0 || layout.normal >= 0 || layout.depth >= 0;
  pt.equiangular = options.equiangular;
  pt.want_camera_transmittance = layout.need_transmittance;

  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int tiles_y = (height + kTileSize - 1) / kTileSize;
  const size_t tiles_total = size_t(tiles_x) * size_t(tiles_y);
  std::atomic<size_t> tiles_done{0};
  std::atomic<uint64_t> total_rays{0}, total_nonfinite{0};
  const int count = std::max(0, sample_end - sample_begin);
  if (count > kMaxExactSamples)
    throw std::invalid_argument(
        "render: " + std::to_string(count) + " samples per pixel in one range; at most " +
        std::to_string(kMaxExactSamples) + " fit the exact sample sums (split the range)");
  if (options.keep_sums) out.sums.assign(img.pixels.size(), 0);

  auto render_tile = [&](size_t tile) {
    set_flush_to_zero();
    const int tx = int(tile % size_t(tiles_x)), ty = int(tile / size_t(tiles_x));
    uint64_t rays = 0, nonfinite = 0;
    std::vector<ExactSum> acc(nch);
    PathRecord record(int(scene.group_names.size()));
    PathTracerOptions tile_pt = pt;
    if (want_record) tile_pt.record = &record;
    for (int y = ty * kTileSize; y < std::min(height, (ty + 1) * kTileSize); ++y) {
      for (int x = tx * kTileSize; x < std::min(width, (tx + 1) * kTileSize); ++x) {
        std::fill(acc.begin(), acc.end(), ExactSum(0));
        const uint64_t pixel_index = uint64_t(y) * uint64_t(width) + uint64_t(x);
        for (int s = sample_begin; s < sample_end; ++s) {
          Sampler sampler(seed, pixel_index, uint64_t(s));
          const Vec2 offset = sample_pixel_filter(scene.film.filter, sampler.next2());
          const Vec2 u_lens = sampler.next2();
          const Ray ray = scene.camera.generate_ray(float(x) + 0.5f + offset.x,
                                                    float(y) + 0.5f + offset.y, u_lens);
          const PathResult r = trace_path(scene, ray, sampler, tile_pt);
          rays += r.rays;
          // A non-finite value would poison the whole pixel: drop the sample, count it.
          if (!r.radiance.is_finite()) {
            ++nonfinite;
          } else {
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
          if (layout.depth >= 0 && std::isfinite(r.depth))
            acc[size_t(layout.depth)] += to_fixed(r.depth);
        }
        const size_t base = size_t(pixel_index) * nch;
        for (size_t c = 0; c < nch; ++c) img.pixels[base + c] = exact_mean(acc[c], count);
        if (options.keep_sums)
          std::copy(acc.begin(), acc.end(), out.sums.begin() + ptrdiff_t(base));
      }
    }
    total_rays += rays;
    total_nonfinite += nonfinite;
    const size_t done = ++tiles_done;
    if (options.on_progress) options.on_progress(done, tiles_total);
  };

  const int threads =
      options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles_total, 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t t = r.begin(); t != r.end(); ++t) render_tile(t);
                      });
  });

  out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.stats.camera_samples = uint64_t(width) * uint64_t(height) * uint64_t(count);
  out.stats.rays = total_rays;
  out.stats.nonfinite_samples = total_nonfinite;

  img.metadata["vesper:scene_hash"] = scene.content_hash;
  img.metadata["vesper:spp"] = std::to_string(count);
  img.metadata["vesper:sample_begin"] = std::to_string(sample_begin);
  img.metadata["vesper:sample_end"] = std::to_string(sample_end);
  img.metadata["vesper:seed"] = std::to_string(seed);
  img.metadata["vesper:renderer_version"] = VESPER_VERSION;
  img.metadata["vesper:render_seconds"] = std::to_string(out.stats.seconds);
  img.metadata["vesper:nonfinite_samples"] = std::to_string(out.stats.nonfinite_samples);
  return out;
}

}  // namespace vesper
