#pragma once
// Quad light: a one-sided emitting parallelogram of uniform radiance,
// sampled uniformly by area. It emits toward normalize(cross(edge1, edge2))
// only and does not reflect light; a zero-area quad emits nothing.
//
// Scene keys ("type": "quad", docs/scene-format.md#lights):
//   corner, edge1, edge2  vec3, scene units      required; the quad is corner + a edge1 + b edge2,
//                                                a, b in [0, 1]
//   radiance              rgb >= 0, W/(sr m^2)   required
//   group                 string                 optional, light group for layers
// Radiance is invariant under the unit scale; the quad is also a surface in
// the accelerator that camera and BSDF rays can hit (scene_builder).
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/lights/light_interface.h"
#include "renderer/math/constants.h"

namespace vesper {

struct QuadLight {
  Vec3 corner, edge1, edge2;
  Vec3 normal;  // normalize(cross(edge1, edge2)): the emitting side
  float area = 0;
  Rgb radiance;

  std::optional<LightSample> sample(const Vec3& p, Vec2 u) const {
    if (area <= 0.f) return std::nullopt;
    const Vec3 q = corner + edge1 * u.x + edge2 * u.y;
    const Vec3 d = q - p;
    const float dist2 = length_squared(d);
    if (!(dist2 > 0.f)) return std::nullopt;
    const float dist = std::sqrt(dist2);
    const Vec3 wi = d / dist;
    const float cos_l = -dot(wi, normal);
    if (cos_l <= 0.f) return std::nullopt;
    return LightSample{radiance, wi, dist, dist2 / (cos_l * area), false};
  }
  float pdf(const Vec3& wi, float distance) const {
    const float cos_l = -dot(wi, normal);
    if (cos_l <= 0.f || area <= 0.f) return 0.f;
    return distance * distance / (cos_l * area);
  }
  Rgb emitted(const Vec3& wi) const { return dot(wi, normal) < 0.f ? radiance : Rgb{}; }
  Rgb intensity_toward(const Vec3& /*w_from_light*/) const { return {}; }
  float power(float /*scene_radius*/) const { return kPi * area * radiance.average(); }
  std::optional<LightBounds> bounds() const {
    const Vec3 far = corner + edge1 + edge2;
    const Vec3 lo = min(min(corner, far), min(corner + edge1, corner + edge2));
    const Vec3 hi = max(max(corner, far), max(corner + edge1, corner + edge2));
    return LightBounds{lo, hi, false, normal, 0.f, true};
  }
};

}  // namespace vesper
