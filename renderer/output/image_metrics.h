#pragma once
// Image error metrics for time-against-error measurements. relMSE is pinned
// by DESIGN.md: mean over pixels and RGB channels of (x - r)^2 / (r^2 + 0.01),
// with r the reference. Fireflies as issue 11 counts them: pixels whose
// luminance is more than 10x the median of their 5x5 neighbourhood.
// (Moves to compositor/ with the regression tools.)
#include <algorithm>
#include <stdexcept>
#include <vector>

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

// Fraction of pixels whose luminance (Rec.709 weights) exceeds `ratio` times
// the median luminance of the (2 radius + 1)^2 window around them (clipped
// at the borders). A pixel on a dark background counts only if it is above
// `floor` too, so that 1e-9 against a median of 0 is not a firefly.
inline double firefly_fraction(const LayeredImage& image, double ratio = 10.0, int radius = 2,
                               double floor = 1e-3) {
  const int cr = image.channel_index("R"), cg = image.channel_index("G"),
            cb = image.channel_index("B");
  if (cr < 0 || cg < 0 || cb < 0)
    throw std::invalid_argument("firefly_fraction: missing R, G or B");
  const int w = image.width, h = image.height;
  if (w <= 0 || h <= 0) return 0.0;
  std::vector<float> lum(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      lum[size_t(y) * size_t(w) + size_t(x)] = 0.2126f * image.at(x, y, size_t(cr)) +
                                               0.7152f * image.at(x, y, size_t(cg)) +
                                               0.0722f * image.at(x, y, size_t(cb));
  std::vector<float> window;
  size_t count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      window.clear();
      for (int yy = std::max(0, y - radius); yy <= std::min(h - 1, y + radius); ++yy)
        for (int xx = std::max(0, x - radius); xx <= std::min(w - 1, x + radius); ++xx)
          window.push_back(lum[size_t(yy) * size_t(w) + size_t(xx)]);
      const auto mid = window.begin() + std::ptrdiff_t(window.size() / 2);
      std::nth_element(window.begin(), mid, window.end());
      const double v = lum[size_t(y) * size_t(w) + size_t(x)];
      if (v > floor && v > ratio * double(*mid)) ++count;
    }
  return double(count) / (double(w) * double(h));
}

}  // namespace vesper
