#include "regress/layer_channels.h"

#include <algorithm>
#include <cmath>

#include "compositor/histogram.h"

namespace vesper::regress {
namespace {

// The variance channel of `layer`'s colour channel `c` ("R", "G", "B").
std::string variance_channel(const std::string& layer, const std::string& c) {
  return layer == kBeautyLayer ? "variance." + c : layer + ".variance." + c;
}

std::string colour_channel(const std::string& layer, const std::string& c) {
  return layer == kBeautyLayer ? c : layer + "." + c;
}

std::optional<std::array<int, 3>> find_rgb(const LayeredImage& image, const std::string& layer,
                                           std::string (*name)(const std::string&,
                                                               const std::string&)) {
  std::array<int, 3> idx{};
  const char* rgb[] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    idx[size_t(c)] = image.channel_index(name(layer, rgb[c]));
    if (idx[size_t(c)] < 0) return std::nullopt;
  }
  return idx;
}

}  // namespace

bool is_noise_channel(const std::string& channel) {
  return channel == "spp" || channel.rfind("variance.", 0) == 0 ||
         channel.find(".variance.") != std::string::npos;
}

std::string layer_of_channel(const std::string& channel) {
  const size_t dot = channel.rfind('.');
  return dot == std::string::npos ? kBeautyLayer : channel.substr(0, dot);
}

std::vector<LayerChannels> find_layers(const LayeredImage& image) {
  std::vector<LayerChannels> layers;
  for (size_t c = 0; c < image.channels.size(); ++c) {
    const std::string& channel = image.channels[c];
    if (is_noise_channel(channel)) continue;
    const std::string name = layer_of_channel(channel);
    auto it = std::find_if(layers.begin(), layers.end(),
                           [&](const LayerChannels& l) { return l.name == name; });
    if (it == layers.end()) it = layers.insert(layers.end(), LayerChannels{name, {}, {}, {}, {}});
    it->channels.push_back(int(c));
  }
  for (LayerChannels& l : layers) {
    l.rgb = find_rgb(image, l.name, colour_channel);
    if (l.rgb) l.variance = find_rgb(image, l.name, variance_channel);
    if (l.channels.size() == 1) l.single = l.channels[0];
  }
  std::stable_partition(layers.begin(), layers.end(),
                        [](const LayerChannels& l) { return l.name == kBeautyLayer; });
  return layers;
}

std::optional<LumaPlane> layer_luminance(const LayeredImage& image, const LayerChannels& layer) {
  if (!layer.rgb && !layer.single) return std::nullopt;
  LumaPlane plane;
  plane.width = image.width;
  plane.height = image.height;
  const size_t n = size_t(image.width) * size_t(image.height), stride = image.channel_count();
  plane.value.resize(n);
  if (layer.variance) plane.variance.resize(n);
  const std::array<double, 3> w = luma_coefficients(LumaWeights::Rec709);
  for (size_t i = 0; i < n; ++i) {
    const float* p = &image.pixels[i * stride];
    if (!layer.rgb) {
      plane.value[i] = p[*layer.single];
      continue;
    }
    const auto& c = *layer.rgb;
    plane.value[i] = luminance(p[c[0]], p[c[1]], p[c[2]], LumaWeights::Rec709);
    if (!layer.variance) continue;
    double sd = 0;
    for (size_t k = 0; k < 3; ++k) sd += w[k] * std::sqrt(double(p[(*layer.variance)[k]]));
    plane.variance[i] = sd * sd;
  }
  return plane;
}

}  // namespace vesper::regress
