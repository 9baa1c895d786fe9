#include "renderer/render/frame.h"

#include <algorithm>
#include <atomic>

#include "renderer/output/metadata_keys.h"
#include "renderer/output/metadata_text.h"
#include "renderer/scene/camera_matrices.h"

namespace vesper {
namespace {

bool group_active(const std::vector<std::string>& active, const std::string& group) {
  const std::string name = group.empty() ? "default" : group;
  return std::find(active.begin(), active.end(), name) != active.end();
}

void switch_off(LightDesc& l) {
  std::visit(
      [](auto& g) {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, QuadLightDesc>)
          g.radiance = Rgb{};
        else if constexpr (std::is_same_v<T, PointLightDesc> || std::is_same_v<T, SpotLightDesc>)
          g.intensity = Rgb{};
        else if constexpr (std::is_same_v<T, SunLightDesc>)
          g.irradiance = Rgb{};
        else {
          g.radiance = Rgb{};
          g.scale = 0;
        }
      },
      l.light);
}

bool layer_has_alpha(const LayerDesc& layer, const SceneDescription& scene) {
  return layer.paths != PathSelection::Surface && !scene.media.empty();
}

// Appends the ns channels of src to the nd channels of dst (both
// pixel-interleaved over `pixels` pixels).
void append_interleaved(std::vector<float>& dst, size_t nd, const std::vector<float>& src,
                        size_t ns, size_t pixels) {
  const size_t n = nd + ns;
  std::vector<float> merged(pixels * n);
  for (size_t p = 0; p < pixels; ++p) {
    std::copy_n(&dst[p * nd], nd, &merged[p * n]);
    std::copy_n(&src[p * ns], ns, &merged[p * n + nd]);
  }
  dst = std::move(merged);
}

// Keeps the channels `keep` of the n channels of src.
std::vector<float> select_interleaved(const std::vector<float>& src, size_t n,
                                      const std::vector<size_t>& keep, size_t pixels) {
  std::vector<float> out(pixels * keep.size());
  for (size_t p = 0; p < pixels; ++p)
    for (size_t k = 0; k < keep.size(); ++k) out[p * keep.size() + k] = src[p * n + keep[k]];
  return out;
}

// The channels whose names start with prefix + ".".
std::vector<size_t> layer_channels(const LayeredImage& img, const std::string& prefix) {
  std::vector<size_t> keep;
  for (size_t c = 0; c < img.channel_count(); ++c)
    if (img.channels[c].rfind(prefix + ".", 0) == 0) keep.push_back(c);
  return keep;
}

}  // namespace

SceneDescription apply_variant(const SceneDescription& desc, const VariantDesc& variant) {
  SceneDescription d = desc;
  for (const auto& [name, o] : variant.media) {
    auto it = std::find_if(d.media.begin(), d.media.end(),
                           [&](const MediumDesc& m) { return m.name == name; });
    if (it == d.media.end()) continue;  // the loader rejects unknown names
    if (o.enabled && !*o.enabled) {
      d.media.erase(it);
      continue;
    }
    std::visit(
        [&](auto& m) {
          if (o.sigma_a) m.sigma_a = *o.sigma_a;
          if (o.sigma_s) m.sigma_s = *o.sigma_s;
          if (o.g) m.g = *o.g;
          if constexpr (std::is_same_v<std::decay_t<decltype(m)>, VdbMediumDesc>) {
            if (o.density_scale) m.density_scale = *o.density_scale;
          } else if (o.density_scale) {
            m.sigma_a *= float(*o.density_scale);
            m.sigma_s *= float(*o.density_scale);
          }
        },
        it->medium);
  }
  if (variant.lights) {
    for (LightDesc& l : d.lights)
      if (!group_active(*variant.lights, l.group)) switch_off(l);
    // Media emission is the group "emission": off unless listed.
    if (!group_active(*variant.lights, "emission"))
      for (MediumDesc& m : d.media)
        if (auto* v = std::get_if<VdbMediumDesc>(&m.medium)) v->emission_scale = 0;
  }
  d.layers.clear();
  return d;
}

namespace {

// What the EXR writer needs from the film and camera (metadata_keys.h).
void set_film_metadata(std::map<std::string, std::string>& meta, const CameraDesc& camera,
                       const FilmDesc& film) {
  const CameraMatrices m = camera_matrices(camera, film);
  meta[metadata_key::kWorldToCamera] = metadata_matrix(m.world_to_camera);
  meta[metadata_key::kWorldToNdc] = metadata_matrix(m.world_to_ndc);
  if (film.pixel_type != ExrPixelType::Float)
    meta[metadata_key::kPixelType] = kExrPixelTypeNames[size_t(film.pixel_type)];
  if (film.compression != ExrCompression::Zip)
    meta[metadata_key::kCompression] = kExrCompressionNames[size_t(film.compression)];
}

}  // namespace

FrameResult render_frame(const SceneDescription& desc, const RenderOptions& options) {
  std::vector<const LayerDesc*> variants;
  RenderOptions base = options;
  base.layers.clear();
  for (const LayerDesc& layer : desc.layers) {
    if (layer.variant) {
      variants.push_back(&layer);
      continue;
    }
    base.layers.push_back({layer.name, layer.paths, layer.lights, layer_has_alpha(layer, desc)});
  }

  // Progress over all passes: each pass has the same number of tiles.
  const size_t passes = 1 + variants.size();
  std::atomic<size_t> pass_index{0};
  auto progress = [&](size_t done, size_t total) {
    if (options.on_progress) options.on_progress(pass_index * total + done, passes * total);
  };
  base.on_progress = progress;

  FrameResult frame;
  RenderResult beauty = render(build_scene(desc), base);
  frame.image = std::move(beauty.image);
  frame.stats = beauty.stats;
  frame.film = std::move(beauty.film);
  frame.crypto = std::move(beauty.crypto);
  // With adaptive sampling the variant layers take the beauty's per-pixel
  // counts, so that every layer of the frame averages the same samples.
  // (An adaptive render always has the spp channel; a float holds counts exactly.)
  std::vector<int64_t> beauty_counts;
  const int spp_channel = frame.image.channel_index(kSppChannel);
  if (spp_channel >= 0 && frame.image.metadata.count(metadata_key::kStopReason)) {
    beauty_counts.resize(size_t(frame.image.width) * size_t(frame.image.height));
    for (size_t p = 0; p < beauty_counts.size(); ++p)
      beauty_counts[p] =
          int64_t(frame.image.pixels[p * frame.image.channel_count() + size_t(spp_channel)]);
  }
  for (const LayerDesc* layer : variants) {
    ++pass_index;
    const SceneDescription vdesc = apply_variant(desc, *layer->variant);
    RenderOptions vo = options;
    vo.aovs = std::vector<Aov>{};
    vo.layers = {{layer->name, layer->paths, layer->lights, layer_has_alpha(*layer, vdesc)}};
    vo.on_progress = progress;
    if (!beauty_counts.empty()) vo.pixel_samples = &beauty_counts;
    const RenderResult r = render(build_scene(vdesc), vo);
    const size_t pixels = size_t(r.image.width) * size_t(r.image.height);
    const size_t nd = frame.image.channel_count(), ns = r.image.channel_count();
    const std::vector<size_t> keep = layer_channels(r.image, layer->name);
    append_interleaved(frame.image.pixels, nd, select_interleaved(r.image.pixels, ns, keep, pixels),
                       keep.size(), pixels);
    if (options.keep_sums) frame.film.append_channels(r.film, keep);
    for (size_t k : keep) frame.image.channels.push_back(r.image.channels[k]);
    frame.stats.seconds += r.stats.seconds;
    frame.stats.rays += r.stats.rays;
    frame.stats.camera_samples += r.stats.camera_samples;
    frame.stats.nonfinite_samples += r.stats.nonfinite_samples;
    ++frame.passes;
  }
  auto& meta = frame.image.metadata;
  meta[metadata_key::kRenderSeconds] = metadata_number(frame.stats.seconds);
  meta[metadata_key::kNonfiniteSamples] = std::to_string(frame.stats.nonfinite_samples);
  meta[metadata_key::kPasses] = std::to_string(frame.passes);
  set_film_metadata(meta, desc.camera, desc.film);
  return frame;
}

}  // namespace vesper
