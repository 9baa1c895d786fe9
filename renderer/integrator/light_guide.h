#pragma once
// Directions toward small lights for the ray that leaves a scattering vertex:
// the strategy for multiple scattering from point, spot and sphere lights.
//
// Light that reaches a vertex x after one more scattering event comes from
// rays that pass near the light: a ray passing at distance h collects about
// (its equiangular angle) / h of single scattering, and h = D sin(theta) for
// a ray at angle theta to the direction toward the light, D away. The density
// 1 / (2 pi^2 sin(theta)) (theta uniform in [0, pi), phi uniform) has that
// 1 / sin(theta) singularity, so the equiangular estimate on the next ray
// stays bounded where phase sampling alone meets a heavy tail (fireflies
// around light shafts and candles). The light is chosen in proportion to
// power / distance^2, blind to cones: a vertex outside a spot light's cone is
// exactly where its shaft is found only through another scattering event.
//
// The guide is one half of a defensive mixture with the phase function (or
// BSDF): the vertex samples from either and weights by f / mixture pdf, so the
// estimator stays unbiased and its weight bounded by 1 / (phase share).
#include <optional>

#include "renderer/lights/light_sampler.h"
#include "renderer/math/vec.h"

namespace vesper {

class LightGuide {
 public:
  // At p, over the sampler's lights that have an aim point (LightBounds::aim).
  LightGuide(const LightSampler& lights, const Vec3& p);

  bool empty() const { return !(total_ > 0.f); }
  // A direction: u_light picks the light, u the direction around it.
  std::optional<Vec3> sample(float u_light, Vec2 u) const;
  // Density (solid angle) of sample() for direction wi (unit).
  float pdf(const Vec3& wi) const;

 private:
  const LightSampler& lights_;
  Vec3 p_;
  float total_ = 0.f;  // sum of power / distance^2 over the aimed lights
  float weight(size_t i) const;
};

}  // namespace vesper
