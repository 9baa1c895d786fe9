#pragma once
// Synthetic multi-layer images with known noise for the comparison tests:
// grey layers whose pixels are means of 4 noisy streams, with the variance
// channels the renderer would write (docs/sampling.md).
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "renderer/output/layered_image.h"

namespace vesper::test {

struct SyntheticLayer {
  std::string name;        // "beauty" (R,G,B + variance.R/G/B) or a layer name (name.R, ...)
  double mean = 0.5;       // every pixel's expectation
  double variance = 0.01;  // of each pixel's mean
  bool with_variance = true;
};

inline LayeredImage synthetic_image(int w, int h, const std::vector<SyntheticLayer>& layers,
                                    uint64_t seed) {
  LayeredImage img;
  img.width = w;
  img.height = h;
  for (const SyntheticLayer& l : layers) {
    const std::string prefix = l.name == "beauty" ? "" : l.name + ".";
    for (const char* c : {"R", "G", "B"}) img.channels.push_back(prefix + c);
    if (l.with_variance)
      for (const char* c : {"R", "G", "B"}) img.channels.push_back(prefix + "variance." + c);
  }
  std::mt19937_64 rng(seed);
  for (int i = 0; i < w * h; ++i)
    for (const SyntheticLayer& l : layers) {
      std::normal_distribution<double> stream(0, std::sqrt(4 * l.variance));
      double s[4], m = 0, ss = 0;
      for (double& x : s) m += (x = l.mean + stream(rng)) / 4;
      for (double x : s) ss += (x - m) * (x - m);
      for (int c = 0; c < 3; ++c) img.pixels.push_back(float(m));  // grey: R = G = B
      if (l.with_variance)
        for (int c = 0; c < 3; ++c) img.pixels.push_back(float(ss / 3 / 4));
    }
  return img;
}

// Multiplies the layer's colour channels (prefix "" for the beauty) in a rectangle.
inline void scale_region(LayeredImage& img, const std::string& prefix, double factor, int x0,
                         int y0, int x1, int y1) {
  for (const char* c : {"R", "G", "B"}) {
    const size_t ch = size_t(img.channel_index(prefix + c));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) img.at(x, y, ch) = float(img.at(x, y, ch) * factor);
  }
}

}  // namespace vesper::test
