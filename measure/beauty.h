#pragma once
// The beauty's R, G, B of an image as a 3-channel image: what bench scores,
// caches and compares (AOVs, layers and alpha play no part in relMSE).
#include "renderer/output/layered_image.h"

namespace vesper::measure {

// Throws std::invalid_argument when R, G or B is missing. Metadata are kept.
LayeredImage beauty_rgb(const LayeredImage& image);

}  // namespace vesper::measure
