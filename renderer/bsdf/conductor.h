#pragma once
// Metal: a GGX/Smith microfacet reflector with the complex Fresnel term of
// (eta, k) per channel.
// - alpha < kSpecularAlpha: a delta mirror (is_specular samples, eval = pdf = 0).
// - otherwise: f = F(wo.wm) D(wm) G2(wo, wi) / (4 |cos_o| |cos_i|), sampled by
//   visible normals; a sample reflected below the surface is returned as
//   nullopt (absorbed), so the sampling density integrates to less than 1.
//   Single scattering only: energy is lost at high roughness (see
//   bsdf_test's glossy furnace).
// Opaque and two-sided: a wo below the surface is handled as its mirror
// image; wi must be on wo's side, else f = pdf = 0.
#include <optional>

#include "renderer/bsdf/bsdf.h"

namespace vesper::bsdf_detail {

Rgb eval(const ConductorBsdf& b, Vec3 wo, Vec3 wi);
float pdf(const ConductorBsdf& b, Vec3 wo, Vec3 wi);
std::optional<BsdfSample> sample(const ConductorBsdf& b, Vec3 wo, float uc, Vec2 u);
// Fresnel reflectance at normal incidence.
Rgb albedo(const ConductorBsdf& b);
inline bool is_delta(const ConductorBsdf& b) { return b.alpha < kSpecularAlpha; }

}  // namespace vesper::bsdf_detail
