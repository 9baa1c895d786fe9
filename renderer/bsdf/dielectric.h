#pragma once
// Glass (pbrt-v4 conventions). The side with local z > 0 is the outside and
// eta = n_inside / n_outside; etap below is the relative index n_t / n_i seen
// from wo (eta when wo is outside, 1 / eta when inside).
// - Smooth (alpha < kSpecularAlpha, or eta == 1 where nothing bends): delta
//   reflection with probability F and f = F / |cos_i|, or delta refraction with
//   probability 1 - F and f = (1 - F) / |cos_i| / etap^2.
// - Rough: Walter et al. 2007 with the generalised half vector
//   wm = normalize(etap wi + wo), sampled by visible normals of wo; reflect with
//   probability F(wo.wm) else refract. Samples that end on the wrong side are
//   returned as nullopt (absorbed).
// Transmission is for radiance transport: divided by etap^2 (radiance is
// compressed into the smaller solid angle of the denser medium), so the
// transmitted weight times etap^2 is what sums with reflection to 1.
// Total internal reflection gives F = 1.
#include <optional>

#include "renderer/bsdf/bsdf.h"

namespace vesper::bsdf_detail {

Rgb eval(const DielectricBsdf& b, Vec3 wo, Vec3 wi);
float pdf(const DielectricBsdf& b, Vec3 wo, Vec3 wi);
std::optional<BsdfSample> sample(const DielectricBsdf& b, Vec3 wo, float uc, Vec2 u);
inline Rgb albedo(const DielectricBsdf&) { return Rgb(1.f); }
inline bool is_delta(const DielectricBsdf& b) { return b.alpha < kSpecularAlpha || b.eta == 1.f; }

}  // namespace vesper::bsdf_detail
