#pragma once
// Point light: isotropic, a delta in position.
//
// Scene keys ("type": "point", docs/scene-format.md#lights):
//   position   vec3, scene units   required
//   intensity  rgb >= 0, W/sr      required
//   radius     number >= 0, scene units  default 0: a sphere light (sphere_cone.h)
//   group      string              optional, light group for layers
// Render space: `intensity` is divided by unit_scale^2 (scene_builder), so
// the irradiance it gives does not depend on the unit scale.
#include <cmath>
#include <optional>

#include "renderer/lights/light_interface.h"
#include "renderer/lights/sphere_cone.h"
#include "renderer/math/constants.h"

namespace vesper {

struct PointLight {
  Vec3 position;
  Rgb intensity;     // W/sr
  float radius = 0;  // 0: a delta light

  std::optional<LightSample> sample(const Vec3& p, Vec2 u) const {
    if (radius > 0.f) return sample_sphere_light(p, position, radius, intensity, u);
    const Vec3 d = position - p;
    const float dist2 = length_squared(d);
    if (!(dist2 > 0.f)) return std::nullopt;
    const float dist = std::sqrt(dist2);
    return LightSample{intensity / dist2, d / dist, dist, 1.f, true};
  }
  float pdf(const Vec3& /*wi*/, float /*distance*/) const { return 0.f; }
  Rgb emitted(const Vec3& /*wi*/) const { return {}; }
  Rgb intensity_toward(const Vec3& /*w_from_light*/) const { return intensity; }
  float power(float /*scene_radius*/) const { return 4.f * kPi * intensity.average(); }
  std::optional<LightBounds> bounds() const { return sphere_bounds(position, radius); }
};

}  // namespace vesper
