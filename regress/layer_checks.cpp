#include "regress/layer_checks.h"

#include <cmath>
#include <random>

#include "compositor/histogram.h"

namespace vesper::regress {
namespace {

bool pixel_nonfinite(const LayeredImage& image, const LayerChannels& layer, size_t pixel) {
  const float* p = &image.pixels[pixel * image.channel_count()];
  for (int c : layer.channels)
    if (!std::isfinite(p[c])) return true;
  return false;
}

// `values` as a grey image: a grey pixel's luminance is its value, whatever the weights.
Histogram log2_luminance_histogram(const std::vector<double>& values, int width, int height) {
  RgbaImage grey(width, height);
  for (size_t i = 0; i < values.size(); ++i)
    for (int c = 0; c < 3; ++c) grey.pixels[i * 4 + size_t(c)] = float(values[i]);
  return log2_histogram(grey, LumaWeights::Rec709);
}

double distance_of(const std::vector<double>& a, const std::vector<double>& b, int w, int h) {
  return wasserstein1(log2_luminance_histogram(a, w, h), log2_luminance_histogram(b, w, h));
}

}  // namespace

NonfiniteCount count_nonfinite(const LayeredImage& golden, const LayerChannels& golden_layer,
                               const LayeredImage& fresh, const LayerChannels& new_layer) {
  NonfiniteCount count;
  const size_t n = size_t(golden.width) * size_t(golden.height);
  for (size_t i = 0; i < n; ++i) {
    const bool g = pixel_nonfinite(golden, golden_layer, i);
    const bool f = pixel_nonfinite(fresh, new_layer, i);
    count.golden += g;
    count.fresh += f;
    if (!f || g) continue;
    ++count.introduced;
    if (count.introduced_at.size() < kMaxPixelsListed)
      count.introduced_at.push_back({int(i % size_t(golden.width)), int(i / size_t(golden.width))});
  }
  return count;
}

HistogramDistance histogram_distance(const LumaPlane& golden, const LumaPlane& fresh) {
  HistogramDistance out;
  out.distance = distance_of(golden.value, fresh.value, golden.width, golden.height);
  std::mt19937_64 rng(0x5eedf00d);  // fixed: the same images always get the same verdict
  std::vector<double> a(golden.value.size()), b(a.size()), null;
  for (int k = 0; k < kHistogramPermutations; ++k) {
    for (size_t i = 0; i < a.size(); ++i) {
      const bool swap = (rng() >> 63) != 0;
      a[i] = swap ? fresh.value[i] : golden.value[i];
      b[i] = swap ? golden.value[i] : fresh.value[i];
    }
    null.push_back(distance_of(a, b, golden.width, golden.height));
  }
  double mean = 0, var = 0;
  for (double d : null) mean += d / double(null.size());
  for (double d : null) var += (d - mean) * (d - mean) / double(null.size() - 1);
  out.noise_level = mean + kHistogramNoiseSds * std::sqrt(var);
  return out;
}

}  // namespace vesper::regress
