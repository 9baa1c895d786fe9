#pragma once
// Equiangular sampling of a distance along a ray toward a point (Kulla &
// Fajardo 2012): t has density proportional to 1 / |x(t) - light|^2, which
// is what makes single scattering from small lights (light shafts) converge.
#include <cmath>
#include <optional>

#include "renderer/math/vec.h"

namespace vesper {

struct EquiangularSegment {
  float delta = 0;  // t of the point on the ray closest to the light
  float dist = 0;   // distance from the light to the ray
  float angle = 0;  // theta_b - theta_a: the angle [ta, tb] subtends at the light
  float ta = 0, tb = 0;

  // nullopt when the light lies on the ray's line (the density degenerates)
  // or the interval is empty.
  static std::optional<EquiangularSegment> make(const Vec3& o, const Vec3& d, const Vec3& light,
                                                float ta, float tb) {
    const Vec3 ol = light - o;
    EquiangularSegment s;
    s.delta = dot(ol, d);
    s.dist = length(ol - d * s.delta);
    if (!(s.dist > 1e-6f * (std::abs(s.delta) + 1e-6f)) || !(tb > ta) || !std::isfinite(tb))
      return std::nullopt;
    s.ta = ta;
    s.tb = tb;
    // One atan2 for the difference (tan(b - a) = h (tb - ta) / (h^2 + (ta -
    // delta)(tb - delta)); the numerator is positive, so atan2 lands in (0,
    // pi)): every pdf needs it, and only sample() needs theta_a itself.
    s.angle = std::atan2(s.dist * (tb - ta), s.dist * s.dist + (ta - s.delta) * (tb - s.delta));
    if (!(s.angle > 0.f)) return std::nullopt;
    return s;
  }
  float theta_a() const { return std::atan2(ta - delta, dist); }
  float sample(float u) const {
    const float t = delta + dist * std::tan(theta_a() + u * angle);
    return std::fmin(std::fmax(t, ta), tb);
  }
  float pdf(float t) const {
    if (t < ta || t > tb) return 0.f;
    const float x = t - delta;
    return dist / (angle * (dist * dist + x * x));
  }
};

}  // namespace vesper
