#pragma once
// One layer of a frame against its golden: NaN/Inf pixels, the luminosity
// histogram distance and, when both renders carry the layer's variance, the
// per-tile tests with Holm's correction (docs/regression.md).
#include "regress/layer_channels.h"
#include "regress/regress_result.h"
#include "regress/suite.h"

namespace vesper::regress {

// Images of the same size; `golden_layer` and `new_layer` describe the same
// layer in each. Fills everything of the LayerResult, its verdict and reasons.
LayerResult compare_layer(const LayeredImage& golden, const LayerChannels& golden_layer,
                          const LayeredImage& fresh, const LayerChannels& new_layer,
                          const Thresholds& thresholds);

}  // namespace vesper::regress
