#include "renderer/render/channel_layout.h"

#include <algorithm>
#include <numeric>

#include "renderer/integrator/path_record.h"
#include "renderer/output/film_sums.h"
#include "renderer/scene/aov_names.h"

namespace vesper {
namespace {

using FE = FirstEvent;

std::vector<size_t> bins_for(const std::vector<FirstEvent>& kinds,
                             std::initializer_list<bool> indirect, const std::vector<int>& groups,
                             int group_count) {
  std::vector<size_t> out;
  for (FirstEvent k : kinds)
    for (bool ind : indirect)
      for (int g : groups) out.push_back(PathRecord::bin(k, ind, g, group_count));
  return out;
}

// The first events whose contributions a transport AOV sums (empty for the
// others), and whether it takes the indirect ones (*_indirect) or the direct.
std::vector<FirstEvent> transport_events(Aov a) {
  switch (a) {
    case Aov::Emission:
      return {FE::SurfaceView, FE::VolumeView};
    case Aov::DiffuseDirect:
    case Aov::DiffuseIndirect:
      return {FE::Diffuse};
    case Aov::SpecularDirect:
    case Aov::SpecularIndirect:
      return {FE::Specular};
    case Aov::VolumeDirect:
    case Aov::VolumeIndirect:
      return {FE::Volume};
    case Aov::Albedo:
    case Aov::Normal:
    case Aov::Depth:
    case Aov::Variance:
    case Aov::Spp:
    case Aov::Cryptomatte:
      break;
  }
  return {};
}
bool transport_indirect(Aov a) {
  return a == Aov::DiffuseIndirect || a == Aov::SpecularIndirect || a == Aov::VolumeIndirect;
}

void add_aov(ChannelLayout& l, Aov a, const std::vector<int>& all_groups) {
  const std::string name(kAovNames[size_t(a)]);
  if (a == Aov::Albedo) {
    l.albedo = l.add_rgb(name);
  } else if (a == Aov::Normal) {
    l.normal = int(l.names.size());
    l.names.insert(l.names.end(), {"normal.X", "normal.Y", "normal.Z"});
  } else if (a == Aov::Variance) {
    l.names.insert(l.names.end(), kVarianceChannels.begin(), kVarianceChannels.end());
  } else if (a == Aov::Spp) {
    l.names.push_back(kSppChannel);
  } else if (a == Aov::Cryptomatte) {
    l.cryptomatte = true;  // its channels come after the summed ones (render/cryptomatte.h)
  } else if (a == Aov::Depth) {
    l.depth = int(l.names.size());
    l.names.push_back("depth.Z");
  } else {
    l.bin_outputs.push_back({l.add_rgb(name), -1,
                             bins_for(transport_events(a), {transport_indirect(a)}, all_groups,
                                      int(all_groups.size()))});
  }
}

// Indices of the layer's light groups (all when it names none); unknown names are skipped.
std::vector<int> groups_of(const Scene& scene, const LayerSelection& layer,
                           const std::vector<int>& all_groups) {
  if (!layer.lights) return all_groups;
  std::vector<int> kept;
  for (const std::string& name : *layer.lights) {
    const auto it = std::find(scene.group_names.begin(), scene.group_names.end(), name);
    if (it != scene.group_names.end()) kept.push_back(int(it - scene.group_names.begin()));
  }
  return kept;
}

void add_layer(ChannelLayout& l, const LayerSelection& layer, const std::vector<int>& kept,
               int groups) {
  std::vector<size_t> bins;
  switch (layer.paths) {
    case PathSelection::All:
      bins = bins_for({FE::SurfaceView, FE::VolumeView, FE::Diffuse, FE::Specular, FE::Volume},
                      {false, true}, kept, groups);
      break;
    case PathSelection::Surface:
      bins = bins_for({FE::SurfaceView, FE::Diffuse, FE::Specular}, {false, true}, kept, groups);
      break;
    case PathSelection::Volume:
      bins = bins_for({FE::VolumeView, FE::Volume}, {false, true}, kept, groups);
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

}  // namespace

namespace {

// The variance channels of the streamed RGB outputs, after every other channel.
void add_layer_variance(ChannelLayout& l) {
  std::vector<int> triples;
  for (const BinOutput& o : l.bin_outputs) triples.push_back(o.channel);
  if (l.albedo >= 0) triples.push_back(l.albedo);
  std::sort(triples.begin(), triples.end());
  for (int first : triples)
    for (int c = 0; c < 3; ++c) {
      l.streamed.push_back(first + c);
      l.names.push_back(variance_channel_of(l.names[size_t(first + c)]));
    }
}

}  // namespace

ChannelLayout layout_for(const Scene& scene, const std::vector<Aov>& aovs,
                         const std::vector<LayerSelection>& layers, bool layer_variance) {
  ChannelLayout l;
  std::vector<int> all_groups(scene.group_names.size());
  std::iota(all_groups.begin(), all_groups.end(), 0);
  for (Aov a : aovs) add_aov(l, a, all_groups);
  const int groups = int(all_groups.size());
  for (const LayerSelection& layer : layers)
    add_layer(l, layer, groups_of(scene, layer, all_groups), groups);
  if (std::find(aovs.begin(), aovs.end(), Aov::Variance) != aovs.end()) l.streamed = {0, 1, 2};
  if (layer_variance) add_layer_variance(l);
  return l;
}

}  // namespace vesper
