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
// (compositor/histogram.h, 256 bins over [-12, 8] stops) of two planes, and
// how far apart noise alone puts them. Noise moves the histograms apart
// too, and at low spp by more than a real change would (dark pixels jump
// stops): both renders draw each pixel from the same distribution when
// nothing changed, so swapping the golden and new values of random pixels
// gives renders that differ by noise only. Their distances (a paired
// permutation test, fixed seed) have a mean and a spread; `noise_level` is
// their mean + kHistogramNoiseSds standard deviations.
struct HistogramDistance {
  double distance = 0;
  double noise_level = 0;
};
constexpr int kHistogramPermutations = 24;
constexpr double kHistogramNoiseSds = 6;

HistogramDistance histogram_distance(const LumaPlane& golden, const LumaPlane& fresh);

}  // namespace vesper::regress
