#pragma once
// Interface optics: Snell refraction and Fresnel reflectance (dielectric,
// complex-index conductor as pbrt-v4's FrComplex, and Schlick's approximation).
#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>

#include "renderer/math/constants.h"
#include "renderer/math/rgb.h"
#include "renderer/math/vec.h"

namespace vesper {

// Unpolarised reflectance of a dielectric interface; eta = n_inside / n_outside
// and the normal points outside. cos_i < 0 means the light arrives from the
// inside, where the relative index is 1/eta. Returns 1 under total internal
// reflection.
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = clamp(cos_i, -1.f, 1.f);
  if (cos_i < 0.f) {
    eta = 1.f / eta;
    cos_i = -cos_i;
  }
  const float sin2_t = (1.f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.f) return 1.f;
  const float cos_t = safe_sqrt(1.f - sin2_t);
  const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float f = 0.5f * (r_parl * r_parl + r_perp * r_perp);
  return std::isfinite(f) ? clamp(f, 0.f, 1.f) : 1.f;
}

// Reflectance of a conductor with complex index eta + i k (relative to the
// outside medium); cos_i is clamped to [0, 1].
inline float fresnel_complex(float cos_i, std::complex<float> eta) {
  cos_i = clamp(cos_i, 0.f, 1.f);
  // Every interface reflects everything at exactly grazing incidence; this
  // also avoids 0/0 for eta == 1.
  if (cos_i == 0.f || std::norm(eta) == 0.f) return 1.f;
  const float sin2_i = 1.f - cos_i * cos_i;
  const std::complex<float> sin2_t = sin2_i / (eta * eta);
  const std::complex<float> cos_t = std::sqrt(1.f - sin2_t);
  const std::complex<float> r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const std::complex<float> r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float f = 0.5f * (std::norm(r_parl) + std::norm(r_perp));
  return std::isfinite(f) ? clamp(f, 0.f, 1.f) : 1.f;
}
inline Rgb fresnel_complex(float cos_i, const Rgb& eta, const Rgb& k) {
  Rgb f;
  for (int c = 0; c < 3; ++c) f[c] = fresnel_complex(cos_i, {eta[c], k[c]});
  return f;
}

// (1 - cos)^5, the Schlick interpolation weight.
inline float schlick_weight(float cos_theta) {
  const float m = clamp(1.f - cos_theta, 0.f, 1.f);
  const float m2 = m * m;
  return m2 * m2 * m;
}
inline Rgb fresnel_schlick(const Rgb& f0, float cos_theta) {
  return f0 + (Rgb(1.f) - f0) * schlick_weight(cos_theta);
}

struct Refraction {
  Vec3 wt;     // transmitted direction, unit length
  float etap;  // relative index n_t / n_i actually used (eta or 1/eta)
};
// Refracts wi (pointing away from the surface) through the interface with
// normal n, which points to the outside; eta = n_inside / n_outside.
// nullopt under total internal reflection.
inline std::optional<Refraction> refract(const Vec3& wi, Vec3 n, float eta) {
  float cos_i = dot(n, wi);
  if (cos_i < 0.f) {
    eta = 1.f / eta;
    cos_i = -cos_i;
    n = -n;
  }
  const float sin2_t = std::max(0.f, 1.f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.f) return std::nullopt;
  const float cos_t = safe_sqrt(1.f - sin2_t);
  return Refraction{-wi / eta + (cos_i / eta - cos_t) * n, eta};
}

}  // namespace vesper
