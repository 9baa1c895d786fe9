#pragma once
// Warps from the unit square to common domains, with their densities.
#include <cmath>

#include "renderer/math/constants.h"
#include "renderer/math/vec.h"

namespace vesper {

inline Vec2 sample_uniform_disk_concentric(Vec2 u) {
  const float ox = 2.f * u.x - 1.f, oy = 2.f * u.y - 1.f;
  if (ox == 0.f && oy == 0.f) return {0.f, 0.f};
  float r, theta;
  if (std::abs(ox) > std::abs(oy)) {
    r = ox;
    theta = kPiOver4 * (oy / ox);
  } else {
    r = oy;
    theta = kPiOver2 - kPiOver4 * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

inline Vec3 sample_cosine_hemisphere(Vec2 u) {
  const Vec2 d = sample_uniform_disk_concentric(u);
  return {d.x, d.y, safe_sqrt(1.f - d.x * d.x - d.y * d.y)};
}
inline float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0.f ? cos_theta * kInvPi : 0.f;
}

inline Vec3 sample_uniform_sphere(Vec2 u) {
  const float z = 1.f - 2.f * u.x;
  const float r = safe_sqrt(1.f - z * z);
  const float phi = 2.f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniform_sphere_pdf() { return kInv4Pi; }

// Uniform direction in the cone around +z with cos(theta) >= cos_max.
inline Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
  const float cos_t = (1.f - u.x) + u.x * cos_max;
  const float sin_t = safe_sqrt(1.f - cos_t * cos_t);
  const float phi = 2.f * kPi * u.y;
  return {std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t};
}
inline float uniform_cone_pdf(float cos_max) { return 1.f / (2.f * kPi * (1.f - cos_max)); }

}  // namespace vesper
