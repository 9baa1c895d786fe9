#pragma once
// One-sided emitting parallelogram, sampled uniformly by area. It does not reflect.
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/lights/light_sample.h"
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
  // Solid-angle density of sample() producing a hit at distance `dist` along wi.
  float pdf(const Vec3& wi, float dist) const {
    const float cos_l = -dot(wi, normal);
    if (cos_l <= 0.f || area <= 0.f) return 0.f;
    return dist * dist / (cos_l * area);
  }
  Rgb emitted(const Vec3& wi_toward_light) const {
    return dot(wi_toward_light, normal) < 0.f ? radiance : Rgb{};
  }
  float power() const { return kPi * area * radiance.average(); }
};

}  // namespace vesper
