#pragma once
// The checks of a layer that need no noise model: NaN/Inf pixels and the
// distance between the luminosity histograms.
#include <cstdint>
#include <vector>

#include "regress/layer_channels.h"
#include "regress/regress_result.h"

namespace vesper::regress {

struct NonfiniteCount {
  uint64_t golden = 0, fresh = 0;    // pixels with a NaN/Inf in any of the layer's channels
  uint64_t introduced = 0;           // of those, pixels finite in the golden
  std::vector<Pixel> introduced_at;  // the first kMaxPixelsListed, row-major
};
constexpr size_t kMaxPixelsListed = 16;

// Images of the same size; `golden_layer` and `new_layer` name the same layer in each.
NonfiniteCount count_nonfinite(const LayeredImage& golden, const LayerChannels& golden_layer,
                               const LayeredImage& fresh, const LayerChannels& new_layer);

// Wasserstein-1 distance (stops) between the log2-luminance histograms
// (compositor/histogram.h, 256 bins over [-12, 8] stops) of two planes.
double histogram_distance(const LumaPlane& golden, const LumaPlane& fresh);

}  // namespace vesper::regress
