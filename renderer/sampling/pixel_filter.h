#pragma once
// Pixel reconstruction filters, applied by importance sampling the filter
// (pbrt-v4 style): each sample's position is drawn from the filter and every
// sample weighs the same, so a pixel is a plain mean of its samples and
// sample ranges merge exactly by sample count.
#include <cmath>

#include "renderer/math/constants.h"
#include "renderer/math/vec.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

inline constexpr float kGaussianSigma = 0.5f;   // pixels
inline constexpr float kGaussianRadius = 1.5f;  // pixels (3 sigma)

// Inverse error function. Hand-written (M. Giles, "Approximating the erfinv
// function", 2010, single precision) because the C++ library has none and
// this one line does not justify a dependency.
inline float erf_inv(float x) {
  float w = -std::log(std::max(1e-30f, (1.f - x) * (1.f + x)));
  float p;
  if (w < 5.f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

// One axis of a Gaussian truncated to [-radius, radius], by CDF inversion.
inline float sample_truncated_gaussian(float u) {
  const float a = std::erf(-kGaussianRadius / (kGaussianSigma * std::sqrt(2.f)));
  const float e = a + u * (-2.f * a);  // uniform in [erf(-r), erf(r)]
  return clamp(kGaussianSigma * std::sqrt(2.f) * erf_inv(e), -kGaussianRadius, kGaussianRadius);
}

// Offset from the pixel centre for a sample.
inline Vec2 sample_pixel_filter(FilterType filter, Vec2 u) {
  if (filter == FilterType::Box) return {u.x - 0.5f, u.y - 0.5f};
  return {sample_truncated_gaussian(u.x), sample_truncated_gaussian(u.y)};
}

}  // namespace vesper
