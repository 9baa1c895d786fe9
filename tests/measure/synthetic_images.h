#pragma once
// Synthetic RGB images for measure/'s tests: a known "truth" and unbiased
// Gaussian estimates of it with a known per-pixel standard deviation.
#include <random>

#include "renderer/output/layered_image.h"

namespace vesper::measure::synth {

inline LayeredImage rgb_image(int w, int h, float value = 0) {
  LayeredImage img;
  img.width = w;
  img.height = h;
  img.channels = {"R", "G", "B"};
  img.pixels.assign(size_t(w) * size_t(h) * 3, value);
  return img;
}

// A truth that varies over the image (0.2 .. 2), so the relMSE's per-pixel
// weights 1 / (r^2 + 0.01) are not all equal.
inline LayeredImage truth_image(int w, int h) {
  LayeredImage img = rgb_image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (size_t c = 0; c < 3; ++c)
        img.at(x, y, c) = float(0.2 + 1.8 * double(x + y + int(c)) / double(w + h + 1));
  return img;
}

// truth + N(0, (sigma_rel * truth)^2) in every pixel and channel.
inline LayeredImage noisy(const LayeredImage& truth, double sigma_rel, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  LayeredImage img = truth;
  for (float& v : img.pixels) v = float(v + sigma_rel * v * n(rng));
  return img;
}

}  // namespace vesper::measure::synth
