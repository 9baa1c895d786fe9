#pragma once
// The two pictures of what changed in a layer, as display-referred images:
// - the difference heat map: |new - golden| luminance per pixel on viridis,
//   scaled so the 99th percentile reaches the top (one firefly cannot wash
//   the rest out); NaN/Inf in either render in magenta, outside the ramp;
// - the significance map: the comparison's per-tile Z over a dimmed grey
//   copy of the image; tiles whose change counts coloured on the diverging
//   ramp (blue darker, red brighter), the rest left grey.
#include <cstdint>
#include <vector>

#include "compositor/rgba_image.h"
#include "regress/regress_result.h"

namespace vesper::regress {

struct HeatMap {
  RgbaImage image;         // display-referred
  double top = 0;          // |luminance difference| at the top of the ramp
  uint64_t nonfinite = 0;  // pixels NaN or infinite in either render (magenta)
};

// Both scene-linear, the same size (std::invalid_argument otherwise).
HeatMap difference_heat_map(const RgbaImage& golden, const RgbaImage& fresh);

// Which tiles count: layer.tile_significant when the comparison filled it,
// else the `significant_tiles` tiles of largest |Z| (what Holm, Bonferroni
// and Benjamini-Hochberg all flag: the smallest p-values). Empty when the
// layer has no tile grid.
std::vector<uint8_t> significant_tile_mask(const LayerResult& layer);

struct SignificanceMap {
  RgbaImage image;     // display-referred
  double z_scale = 0;  // |Z| at the ends of the diverging ramp
};

// `backdrop` the display-referred layer (for orientation), the size the
// tile grid covers. Throws std::invalid_argument when the layer has no
// usable tile grid for it.
SignificanceMap significance_map(const LayerResult& layer, const RgbaImage& backdrop);

}  // namespace vesper::regress
