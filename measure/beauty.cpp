#include "measure/beauty.h"

#include <stdexcept>

namespace vesper::measure {

LayeredImage beauty_rgb(const LayeredImage& image) {
  const int idx[3] = {image.channel_index("R"), image.channel_index("G"), image.channel_index("B")};
  for (int c : idx)
    if (c < 0) throw std::invalid_argument("the image has no R, G and B channels");
  LayeredImage out;
  out.width = image.width;
  out.height = image.height;
  out.channels = {"R", "G", "B"};
  out.metadata = image.metadata;
  out.pixels.resize(size_t(image.width) * size_t(image.height) * 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (size_t c = 0; c < 3; ++c) out.at(x, y, c) = image.at(x, y, size_t(idx[c]));
  return out;
}

}  // namespace vesper::measure
