#pragma once
// How much a light at a known place may give a shading point: the one-node
// importance of Conty & Kulla 2018's light tree (power, distance, the
// orientation of the surface and of the emitter), as in pbrt-v4's
// LightBounds::Importance. The selection (light_sampler.h) only needs an
// estimate, but a zero must be a proof: a light called dark here gets no
// shadow rays at that point, so the bounds below are conservative.
#include <algorithm>
#include <cmath>
#include <optional>

#include "renderer/lights/light_bounds.h"

namespace vesper {

// cos(max(0, theta - theta_u)) from the cosines and sines of both angles:
// the largest cosine any direction within theta_u of the centre direction
// can have to the axis.
inline float cos_widened(float cos_theta, float cos_u, float sin_u) {
  if (cos_theta >= cos_u) return 1.f;
  const float sin_theta = std::sqrt(std::max(0.f, 1.f - cos_theta * cos_theta));
  return cos_theta * cos_u + sin_theta * sin_u;
}

// A slack on every "cannot reach" test so that rounding in the light's own
// sample() never turns a lit point dark.
inline constexpr float kImportanceSlack = 1e-4f;

// The importance of a light with bounds `b` and power `power` at p. `n`: the
// unit normal of an opaque surface, on the side that reflects (zero in a
// medium or for a transmissive surface: every direction counts). nullopt:
// the light provably gives p nothing.
// `near`: the distance clamp as a fraction of the squared bounding radius.
inline std::optional<float> light_importance(const LightBounds& b, float power, const Vec3& p,
                                             const Vec3& n, float near = 1.f) {
  const Vec3 centre = (b.lo + b.hi) * 0.5f;
  const float r2 = length_squared(b.hi - b.lo) * 0.25f;  // bounding sphere, squared radius
  const Vec3 to_light = centre - p;
  const float d2 = length_squared(to_light);
  const float importance = power / std::max({d2, r2 * near, 1e-12f});
  // Inside the bounding sphere every direction may reach the light.
  if (!(d2 > r2)) return importance;
  const float d = std::sqrt(d2);
  const Vec3 w = to_light / d;  // toward the light's centre
  const float sin_u = std::sqrt(r2 / d2), cos_u = std::sqrt(std::max(0.f, 1.f - r2 / d2));
  float cos_surface = 1.f;
  if (n.x != 0.f || n.y != 0.f || n.z != 0.f) {
    cos_surface = cos_widened(dot(n, w), cos_u, sin_u);
    if (cos_surface < -kImportanceSlack) return std::nullopt;  // all of it below the horizon
  }
  float emitter = 1.f;
  if (b.cos_cone > -1.f) {
    const float cos_emit = cos_widened(-dot(b.axis, w), cos_u, sin_u);
    if (cos_emit < b.cos_cone - kImportanceSlack) return std::nullopt;  // p outside its cone
    if (b.cosine) emitter = std::max(cos_emit, 0.f);
  }
  return importance * std::max(cos_surface, 0.f) * emitter;
}

}  // namespace vesper
