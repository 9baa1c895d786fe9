#pragma once
// How an EXR's channels group into layers for the comparison: `R,G,B,A` are
// the beauty, `fog.R` belongs to "fog", `depth.Z` to "depth". A layer's noise
// channels (`variance.R/G/B` for the beauty, `<layer>.variance.R/G/B` for the
// others; docs/sampling.md) and the `spp` count describe the estimate, not
// the picture: they belong to no layer (but still count when channels are
// added or go missing).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "renderer/output/layered_image.h"

namespace vesper::regress {

constexpr const char* kBeautyLayer = "beauty";

struct LayerChannels {
  std::string name;                            // "beauty", "fog", "albedo", "depth", ...
  std::vector<int> channels;                   // every channel of the layer, in image order
  std::optional<std::array<int, 3>> rgb;       // its R, G, B
  std::optional<std::array<int, 3>> variance;  // variance of the mean of R, G, B
  std::optional<int> single;                   // the one channel of a single-channel layer
};

// True for variance and sample-count channels (no layer owns them).
bool is_noise_channel(const std::string& channel);

// The layer a channel belongs to ("beauty" for names without a dot).
std::string layer_of_channel(const std::string& channel);

// Every layer of `image`, the beauty first, then in the order of their first channel.
std::vector<LayerChannels> find_layers(const LayeredImage& image);

// Per pixel (row-major): the layer's luminance (Rec.709 weights) or its
// single channel, and the variance of that value when the layer has variance
// channels. R, G and B of a sample come from the same path and are
// positively correlated; their covariances are not stored, so the variance of
// the luminance takes them as fully correlated, (sum_c w_c sd_c)^2: an upper
// bound, exact for grey light, never an underestimate that would raise
// false alarms.
struct LumaPlane {
  int width = 0, height = 0;
  std::vector<double> value;
  std::vector<double> variance;  // empty without variance channels
};

// nullopt for layers that are neither RGB nor single-channel (normal.X/Y/Z).
std::optional<LumaPlane> layer_luminance(const LayeredImage& image, const LayerChannels& layer);

}  // namespace vesper::regress
