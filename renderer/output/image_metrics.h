#pragma once
// Image error metrics for time-against-error measurements. relMSE is pinned
// by DESIGN.md: mean over pixels and RGB channels of (x - r)^2 / (r^2 + 0.01),
// with r the reference. (Moves to compositor/ with the regression tools.)
#include <stdexcept>

#include "renderer/output/layered_image.h"

namespace vesper {

inline double relative_mse(const LayeredImage& image, const LayeredImage& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("relative_mse: image sizes differ");
  const int ci[3] = {image.channel_index("R"), image.channel_index("G"), image.channel_index("B")};
  const int cr[3] = {reference.channel_index("R"), reference.channel_index("G"),
                     reference.channel_index("B")};
  for (int c = 0; c < 3; ++c)
    if (ci[c] < 0 || cr[c] < 0) throw std::invalid_argument("relative_mse: missing R, G or B");
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = image.at(x, y, size_t(ci[c])), r = reference.at(x, y, size_t(cr[c]));
        sum += (v - r) * (v - r) / (r * r + 0.01);
      }
  return sum / (3.0 * image.width * image.height);
}

}  // namespace vesper
