#pragma once
// Distant light. With angle 0 it is a delta directional light of irradiance
// E; otherwise a uniform disk of angular diameter `angle` whose radiance
// L = E / (pi sin^2(theta_max)) gives irradiance E perpendicular to it.
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/lights/light_sample.h"
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

  std::optional<LightSample> sample(Vec2 u) const {
    constexpr float inf = std::numeric_limits<float>::infinity();
    if (is_delta()) return LightSample{irradiance, direction, inf, 1.f, true};
    const Vec3 wi = frame.to_world(sample_uniform_cone(u, cos_max));
    return LightSample{radiance, normalize(wi), inf, uniform_cone_pdf(cos_max), false};
  }
  float pdf(const Vec3& wi) const {
    if (is_delta() || dot(wi, direction) < cos_max) return 0.f;
    return uniform_cone_pdf(cos_max);
  }
  Rgb emitted(const Vec3& wi) const {
    if (is_delta() || dot(wi, direction) < cos_max) return {};
    return radiance;
  }
  float power(float scene_radius) const { return kPi * sqr(scene_radius) * irradiance.average(); }
};

}  // namespace vesper
