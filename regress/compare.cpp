// compare_frames: the frame-level checks (size, channel sets, which layers)
// around compare_layer, and the scene's verdict and reasons.
#include "regress/compare.h"

#include <algorithm>

#include <fmt/format.h>

#include "regress/compare_layer.h"
#include "regress/layer_channels.h"
#include "regress/verdicts.h"

namespace vesper::regress {
namespace {

// The layer a channel is about: its own, or for noise channels the layer
// whose estimate they describe ("fog.variance.R" -> fog, "spp" -> beauty).
std::string owner_layer(const std::string& channel) {
  if (!is_noise_channel(channel)) return layer_of_channel(channel);
  const size_t v = channel.find(".variance.");
  return v == std::string::npos ? kBeautyLayer : channel.substr(0, v);
}

bool selected(const std::vector<std::string>* layers, const std::string& layer) {
  return !layers || std::find(layers->begin(), layers->end(), layer) != layers->end();
}

// Channels of `a` that `b` lacks, among the selected layers'.
std::vector<std::string> channels_not_in(const LayeredImage& a, const LayeredImage& b,
                                         const std::vector<std::string>* layers) {
  std::vector<std::string> out;
  for (const std::string& c : a.channels)
    if (b.channel_index(c) < 0 && selected(layers, owner_layer(c))) out.push_back(c);
  return out;
}

const LayerChannels* find_layer(const std::vector<LayerChannels>& layers, const std::string& name) {
  for (const LayerChannels& l : layers)
    if (l.name == name) return &l;
  return nullptr;
}

std::string layer_list(const std::vector<LayerChannels>& layers) {
  std::string s;
  for (const LayerChannels& l : layers) s += (s.empty() ? "" : ", ") + l.name;
  return s.empty() ? "none" : s;
}

// The layers to compare: the requested ones, or every layer of either image.
std::vector<std::string> layers_to_compare(const std::vector<LayerChannels>& golden,
                                           const std::vector<LayerChannels>& fresh,
                                           const std::vector<std::string>* requested) {
  if (requested) return *requested;
  std::vector<std::string> names;
  for (const auto* set : {&golden, &fresh})
    for (const LayerChannels& l : *set)
      if (std::find(names.begin(), names.end(), l.name) == names.end()) names.push_back(l.name);
  return names;
}

LayerResult absent_layer(const std::string& name, const std::vector<LayerChannels>& golden,
                         const std::vector<LayerChannels>& fresh) {
  LayerResult out;
  out.layer = name;
  const LayerChannels* g = find_layer(golden, name);
  const LayerChannels* f = find_layer(fresh, name);
  if (!g && !f) {
    out.verdict = Verdict::Error;
    out.reasons.push_back(
        fmt::format("no layer \"{}\" in the golden or the new render "
                    "(golden layers: {}; new: {})",
                    name, layer_list(golden), layer_list(fresh)));
  } else {
    out.verdict = Verdict::Regressed;
    out.reasons.push_back(g ? "missing in the new render"
                            : "not in the golden (a new layer; update the goldens if intended)");
  }
  return out;
}

// A layer whose channel set changed is named as regressed too.
void note_channel_changes(const SceneResult& scene, LayerResult& layer) {
  for (const auto& [list, what] :
       {std::pair{&scene.channels_missing, "missing"}, std::pair{&scene.channels_added, "added"}}) {
    std::string names;
    for (const std::string& c : *list)
      if (owner_layer(c) == layer.layer) names += (names.empty() ? "" : ", ") + c;
    if (names.empty()) continue;
    layer.verdict = worse(layer.verdict, Verdict::Regressed);
    layer.reasons.push_back(fmt::format("channels {}: {}", what, names));
  }
}

}  // namespace

SceneResult compare_frames(const LayeredImage& golden, const LayeredImage& fresh,
                           const std::vector<std::string>* layers, const Thresholds& thresholds) {
  SceneResult scene;
  if (golden.width != fresh.width || golden.height != fresh.height) {
    scene.verdict = Verdict::Regressed;
    scene.reasons.push_back(fmt::format("resolution changed from {}x{} to {}x{}: not compared",
                                        golden.width, golden.height, fresh.width, fresh.height));
    return scene;
  }
  scene.channels_missing = channels_not_in(golden, fresh, layers);
  scene.channels_added = channels_not_in(fresh, golden, layers);
  const std::vector<LayerChannels> g = find_layers(golden), f = find_layers(fresh);
  for (const std::string& name : layers_to_compare(g, f, layers)) {
    const LayerChannels* gl = find_layer(g, name);
    const LayerChannels* fl = find_layer(f, name);
    LayerResult layer =
        gl && fl ? compare_layer(golden, *gl, fresh, *fl, thresholds) : absent_layer(name, g, f);
    note_channel_changes(scene, layer);
    scene.layers.push_back(std::move(layer));
  }
  // Listed at the scene too: noise channels (variance, spp) belong to no layer.
  for (const auto& [list, what] :
       {std::pair{&scene.channels_missing, "missing"}, std::pair{&scene.channels_added, "added"}}) {
    if (list->empty()) continue;
    std::string names;
    for (const std::string& c : *list) names += (names.empty() ? "" : ", ") + c;
    scene.verdict = Verdict::Regressed;
    scene.reasons.push_back(fmt::format("channels {}: {}", what, names));
  }
  summarize_layers(scene);
  return scene;
}

}  // namespace vesper::regress
