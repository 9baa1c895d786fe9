#pragma once
// Which channels a render writes and where each value goes: the beauty
// R,G,B,A, then the AOVs and the layers in the order they were asked for
// (in memory; an EXR file lists them in OpenEXR's order, docs/scene-format.md
// "Channel order"). Internal to render/.
#include <string>
#include <vector>

#include "renderer/render/render.h"

namespace vesper {

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
  bool cryptomatte = false;  // count first hits per shape (render/cryptomatte.h)
  // Channels whose per-stream sums are kept for their variance (FilmSums::streamed).
  std::vector<int> streamed;
  std::vector<std::string> names{"R", "G", "B", "A"};

  int add_rgb(const std::string& prefix) {
    const int at = int(names.size());
    names.insert(names.end(), {prefix + ".R", prefix + ".G", prefix + ".B"});
    return at;
  }
};

// With Aov::Variance the beauty is streamed; with `layer_variance` also every
// RGB AOV and layer, each with its `<name>.variance.R/G/B` channels at the end.
ChannelLayout layout_for(const Scene& scene, const std::vector<Aov>& aovs,
                         const std::vector<LayerSelection>& layers, bool layer_variance = false);

}  // namespace vesper
