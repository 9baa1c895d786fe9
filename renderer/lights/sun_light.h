#pragma once
// Sun light: a distant light. With angle 0 it is a delta directional light of
// irradiance E; otherwise a uniform disk of angular diameter `angle` whose
// radiance L = E / (pi sin^2(theta_max)) gives irradiance E perpendicular to
// it.
//
// Scene keys ("type": "sun", docs/scene-format.md#lights):
//   direction   vec3, non-zero (normalized)   required, from the scene toward the sun
//   irradiance  rgb >= 0, W/m^2               required, on a surface facing the sun
//   angle       degrees, 0 <= a < 90          default 0.53, angular diameter; 0 = delta
//   group       string                        optional, light group for layers
// Irradiance is invariant under the unit scale.
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/lights/light_interface.h"
#include "renderer/math/constants.h"
#include "renderer/math/frame.h"
#include "renderer/sampling/warp.h"

namespace vesper {

struct SunLight {
  Vec3 direction;  // unit, toward the sun
  Rgb irradiance;
  float cos_max = 1.f;  // 1 = delta
  Frame frame;
  Rgb radiance;  // for the finite disk

  bool is_delta() const { return cos_max >= 1.f; }

  std::optional<LightSample> sample(const Vec3& /*p*/, Vec2 u) const {
    constexpr float inf = std::numeric_limits<float>::infinity();
    if (is_delta()) return LightSample{irradiance, direction, inf, 1.f, true};
    const Vec3 wi = frame.to_world(sample_uniform_cone(u, cos_max));
    return LightSample{radiance, normalize(wi), inf, uniform_cone_pdf(cos_max), false};
  }
  float pdf(const Vec3& wi, float /*distance*/) const {
    if (is_delta() || dot(wi, direction) < cos_max) return 0.f;
    return uniform_cone_pdf(cos_max);
  }
  Rgb intensity_toward(const Vec3& /*w_from_light*/) const { return {}; }
  Rgb emitted(const Vec3& wi) const {
    if (is_delta() || dot(wi, direction) < cos_max) return {};
    return radiance;
  }
  // What crosses the scene's bounding disk.
  float power(float scene_radius) const { return kPi * sqr(scene_radius) * irradiance.average(); }
  std::optional<LightBounds> bounds() const { return std::nullopt; }
};

}  // namespace vesper
