#pragma once
// The cone of directions a sphere subtends from a point outside it, sampled
// uniformly by solid angle (pbrt-v4's Sphere::Sample(ctx, u)): the sampling
// of point and spot lights with a radius (sphere lights).
#include <cmath>
#include <optional>

#include "renderer/lights/light_bounds.h"
#include "renderer/lights/light_sample.h"
#include "renderer/math/constants.h"
#include "renderer/math/frame.h"

namespace vesper {

class SphereCone {
 public:
  // nullopt when p is inside the sphere (or on it).
  static std::optional<SphereCone> toward(const Vec3& p, const Vec3& center, float radius) {
    const Vec3 d = center - p;
    const float dist2 = length_squared(d);
    const float r2 = radius * radius;
    if (!(dist2 > r2)) return std::nullopt;
    SphereCone c;
    c.dist_ = std::sqrt(dist2);
    c.r2_ = r2;
    c.frame_ = Frame::from_normal(d / c.dist_);
    const float sin2_max = r2 / dist2;
    c.cos_max_ = std::sqrt(std::max(0.f, 1.f - sin2_max));
    // 1 - cos without cancellation for small spheres.
    c.one_minus_cos_max_ = sin2_max / (1.f + c.cos_max_);
    return c;
  }

  // 1 - cos of the cone's half-angle: the solid angle is 2π times this.
  float one_minus_cos_max() const { return one_minus_cos_max_; }
  float pdf() const { return 1.f / (2.f * kPi * one_minus_cos_max_); }
  bool contains(const Vec3& wi) const { return dot(wi, frame_.n) >= cos_max_; }

  // A direction uniform in the cone and the distance to the sphere's near
  // side along it.
  Vec3 sample(Vec2 u, float* distance) const {
    const float one_minus_cos = u.x * one_minus_cos_max_;
    const float cos_t = 1.f - one_minus_cos;
    const float sin2_t = std::max(0.f, one_minus_cos * (2.f - one_minus_cos));
    const float sin_t = std::sqrt(sin2_t), phi = 2.f * kPi * u.y;
    const Vec3 wi = frame_.to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t});
    // Near root of |p + t wi - center| = r (at the cone's rim the two meet).
    const float b = dist_ * cos_t, disc = std::max(0.f, r2_ - dist_ * dist_ * sin2_t);
    *distance = std::max(0.f, b - std::sqrt(disc));
    return wi;
  }

 private:
  Frame frame_;
  float dist_ = 0, r2_ = 0, cos_max_ = 1, one_minus_cos_max_ = 0;
};

// A point or spot light of radius r > 0 seen from p: the sphere emits the
// uniform radiance I / (π r²) (I the light's intensity toward p), which
// gives the point light's power and, once the whole sphere is above the
// horizon, its irradiance I cos θ / d². Returned as radiance / pdf with
// pdf 1 and is_delta, like a delta light: no ray hits the sphere (it is not
// geometry), so light sampling is its only strategy. As r -> 0 the value
// tends to I / d², the point light's.
inline std::optional<LightSample> sample_sphere_light(const Vec3& p, const Vec3& center,
                                                      float radius, const Rgb& intensity, Vec2 u) {
  const auto cone = SphereCone::toward(p, center, radius);
  if (!cone) return std::nullopt;
  float distance = 0.f;
  const Vec3 wi = cone->sample(u, &distance);
  const float radiance_over_pdf = 2.f * cone->one_minus_cos_max() / (radius * radius);
  return LightSample{intensity * radiance_over_pdf, wi, distance, 1.f, true};
}

inline LightBounds sphere_bounds(const Vec3& center, float radius) {
  return {center - Vec3(radius), center + Vec3(radius), radius > 0.f};
}

}  // namespace vesper
