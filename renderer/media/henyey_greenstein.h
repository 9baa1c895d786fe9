#pragma once
// Henyey-Greenstein phase function. Directions point away from the scattering
// point: wo toward the viewer, wi toward the light; g > 0 scatters forward,
// i.e. favours wi = -wo. Sampling is exact, so f / pdf = 1.
#include <cmath>

#include "renderer/math/constants.h"
#include "renderer/math/frame.h"

namespace vesper {

// Density in terms of cos_theta = dot(wo, wi) (pbrt-v4 convention: the
// scattering angle is between -wo and wi).
inline float henyey_greenstein(float cos_theta, float g) {
  const float denom = 1.f + g * g + 2.f * g * cos_theta;
  return kInv4Pi * (1.f - g * g) / (denom * safe_sqrt(denom));
}

struct HgPhase {
  float g = 0;
  float eval(const Vec3& wo, const Vec3& wi) const { return henyey_greenstein(dot(wo, wi), g); }
  float pdf(const Vec3& wo, const Vec3& wi) const { return eval(wo, wi); }
  // Returns wi with density pdf(wo, wi).
  Vec3 sample(const Vec3& wo, Vec2 u) const {
    float cos_theta;  // between -wo and wi
    if (std::abs(g) < 1e-3f) {
      cos_theta = 1.f - 2.f * u.x;
    } else {
      const float s = (1.f - g * g) / (1.f + g - 2.f * g * u.x);
      cos_theta = clamp((1.f + g * g - s * s) / (2.f * g), -1.f, 1.f);
    }
    const float sin_theta = safe_sqrt(1.f - cos_theta * cos_theta);
    const float phi = 2.f * kPi * u.y;
    const Frame f = Frame::from_normal(-wo);
    return normalize(f.to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta}));
  }
};

}  // namespace vesper
