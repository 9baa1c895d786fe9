#include "regress/layer_checks.h"

#include <cmath>

#include "compositor/histogram.h"

namespace vesper::regress {
namespace {

bool pixel_nonfinite(const LayeredImage& image, const LayerChannels& layer, size_t pixel) {
  const float* p = &image.pixels[pixel * image.channel_count()];
  for (int c : layer.channels)
    if (!std::isfinite(p[c])) return true;
  return false;
}

Histogram log2_luminance_histogram(const LumaPlane& plane) {
  RgbaImage grey(plane.width, plane.height);
  for (size_t i = 0; i < plane.value.size(); ++i)
    for (int c = 0; c < 3; ++c) grey.pixels[i * 4 + size_t(c)] = float(plane.value[i]);
  // A grey pixel's luminance is its value, whatever the weights.
  return log2_histogram(grey, LumaWeights::Rec709);
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

double histogram_distance(const LumaPlane& golden, const LumaPlane& fresh) {
  return wasserstein1(log2_luminance_histogram(golden), log2_luminance_histogram(fresh));
}

}  // namespace vesper::regress
