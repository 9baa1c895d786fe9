#pragma once
// The film filter's weights around a light tracer's splat (light_tracer.h).
#include <algorithm>
#include <cmath>

#include "renderer/sampling/pixel_filter.h"

namespace vesper {

// The truncated Gaussian's density on one axis, normalised over
// [-kGaussianRadius, kGaussianRadius] as sample_truncated_gaussian draws it.
inline float truncated_gaussian_density(float x) {
  if (!(std::abs(x) <= kGaussianRadius)) return 0.f;
  const float s = kGaussianSigma * std::sqrt(2.f);
  const float norm = kGaussianSigma * std::sqrt(2.f * kPi) * std::erf(kGaussianRadius / s);
  return std::exp(-x * x / (2.f * kGaussianSigma * kGaussianSigma)) / norm;
}

// Calls add(pixel x, pixel y, weight) for every pixel whose filter covers
// raster point (fx, fy). The weights integrate to 1 over the raster for each
// pixel, as the pixel's filter-sampled camera rays do.
template <typename Add>
void filter_splat(FilterType filter, int width, int height, float fx, float fy, Add&& add) {
  if (filter == FilterType::Box) {
    if (fx >= 0.f && fy >= 0.f && fx < float(width) && fy < float(height))
      add(int(fx), int(fy), 1.f);
    return;
  }
  const int x0 = int(std::floor(fx - 0.5f - kGaussianRadius)),
            x1 = int(std::floor(fx - 0.5f + kGaussianRadius));
  const int y0 = int(std::floor(fy - 0.5f - kGaussianRadius)),
            y1 = int(std::floor(fy - 0.5f + kGaussianRadius));
  for (int y = std::max(0, y0); y <= std::min(height - 1, y1 + 1); ++y) {
    const float wy = truncated_gaussian_density(fy - (float(y) + 0.5f));
    if (!(wy > 0.f)) continue;
    for (int x = std::max(0, x0); x <= std::min(width - 1, x1 + 1); ++x) {
      const float wx = truncated_gaussian_density(fx - (float(x) + 0.5f));
      if (wx > 0.f) add(x, y, wx * wy);
    }
  }
}

}  // namespace vesper
