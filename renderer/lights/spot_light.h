#pragma once
// Spot light: a point light whose intensity falls off with a smoothstep
// between the falloff_start and cone_angle half-angles (as pbrt-v4's
// SpotLight).
//
// Scene keys ("type": "spot", docs/scene-format.md#lights):
//   position       vec3, scene units                  required
//   direction      vec3, non-zero (normalized)        required, the cone axis
//   intensity      rgb >= 0, W/sr                     required, on the axis
//   cone_angle     degrees, 0 < a <= 180              required, half-angle: no light outside
//   falloff_start  degrees, 0 <= f <= cone_angle      default cone_angle, half-angle: full
//                                                     intensity inside
//   group          string                             optional, light group for layers
// Render space: `intensity` is divided by unit_scale^2 (scene_builder).
#include <cmath>
#include <optional>

#include "renderer/lights/light_interface.h"
#include "renderer/lights/sphere_cone.h"
#include "renderer/math/constants.h"

namespace vesper {

inline float smoothstep(float a, float b, float x) {
  if (a == b) return x < a ? 0.f : 1.f;
  const float t = clamp((x - a) / (b - a), 0.f, 1.f);
  return t * t * (3.f - 2.f * t);
}

struct SpotLight {
  Vec3 position, direction;       // direction: unit, the cone axis
  Rgb intensity;                  // W/sr on the axis
  float cos_cone = 0.f;           // cos(cone_angle)
  float cos_falloff_start = 0.f;  // cos(falloff_start) >= cos_cone
  float radius = 0;               // 0: a delta light; else a sphere light (sphere_cone.h)

  float falloff(const Vec3& w_from_light) const {
    return smoothstep(cos_cone, cos_falloff_start, dot(w_from_light, direction));
  }
  std::optional<LightSample> sample(const Vec3& p, Vec2 u) const {
    if (radius > 0.f) {  // the cone's profile, from the centre toward p
      const float f = falloff(normalize(p - position));
      if (!(f > 0.f)) return std::nullopt;
      return sample_sphere_light(p, position, radius, intensity * f, u);
    }
    const Vec3 d = position - p;
    const float dist2 = length_squared(d);
    if (!(dist2 > 0.f)) return std::nullopt;
    const float dist = std::sqrt(dist2);
    const Vec3 wi = d / dist;
    const float f = falloff(-wi);
    if (f <= 0.f) return std::nullopt;
    return LightSample{intensity * (f / dist2), wi, dist, 1.f, true};
  }
  float pdf(const Vec3& /*wi*/, float /*distance*/) const { return 0.f; }
  Rgb emitted(const Vec3& /*wi*/) const { return {}; }
  Rgb intensity_toward(const Vec3& w_from_light) const { return intensity * falloff(w_from_light); }
  float power(float /*scene_radius*/) const {
    return intensity.average() * 2.f * kPi * (1.f - 0.5f * (cos_falloff_start + cos_cone));
  }
  std::optional<LightBounds> bounds() const {
    LightBounds b = sphere_bounds(position, radius);
    b.axis = direction;
    b.cos_cone = cos_cone;
    return b;
  }
};

}  // namespace vesper
