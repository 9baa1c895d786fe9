#pragma once
// The closed set of BSDFs. All directions are in the local shading frame
// (z = shading normal) and point away from the surface; `wo` is toward the
// viewer, `wi` toward the light. Values are for radiance transport.
//
// Roughness convention: the scene file gives perceptual roughness r in [0, 1];
// GGX alpha = r^2. An alpha below kSpecularAlpha is treated as a perfectly
// smooth (delta) interface.
#include <optional>
#include <variant>

#include "renderer/math/rgb.h"
#include "renderer/math/vec.h"

namespace vesper {

inline constexpr float kSpecularAlpha = 1e-3f;

// Lambertian reflection. Opaque and two-sided.
struct DiffuseBsdf {
  Rgb albedo;
};
// Metal: GGX/Smith microfacets (visible-normal sampling) with the complex
// Fresnel term of (eta, k) per channel. Opaque and two-sided.
struct ConductorBsdf {
  float alpha = 0;
  Rgb eta, k;
};
// Glass: smooth or rough (Walter et al. 2007) reflection + refraction.
// `eta` = ior of the inside / ior of the outside; the side with local z > 0 is
// the outside.
struct DielectricBsdf {
  float eta = 1.5f;
  float alpha = 0;
};
// Frostbite/Disney combination: Burley diffuse weighted by (1 - metallic) plus
// a GGX/Smith specular lobe with Schlick Fresnel, F0 = lerp(0.04, base_color, metallic).
// Opaque and two-sided.
struct PrincipledBsdf {
  Rgb base_color;
  float metallic = 0;
  float alpha = 0.25f;
};

using Bsdf = std::variant<DiffuseBsdf, ConductorBsdf, DielectricBsdf, PrincipledBsdf>;

struct BsdfSample {
  Rgb f;                     // BSDF value (not multiplied by the cosine)
  Vec3 wi;                   // sampled direction, unit length
  float pdf = 0;             // solid-angle density; for delta lobes the discrete probability
  bool is_specular = false;  // sampled a delta lobe (f and pdf are "delta" quantities)
  bool is_transmission = false;
};

// f(wo, wi); zero for delta lobes.
Rgb bsdf_eval(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi);
// Solid-angle density with which bsdf_sample would return wi; zero for delta lobes.
float bsdf_pdf(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi);
// Samples wi given wo; uc picks a lobe, u samples within it. nullopt = absorbed.
std::optional<BsdfSample> bsdf_sample(const Bsdf& bsdf, const Vec3& wo, float uc, const Vec2& u);
// The diffuse lobe's share of bsdf_eval (all of it for diffuse, none for
// conductor and dielectric, the Burley lobe for principled): splits light
// into the diffuse and specular AOVs.
Rgb bsdf_eval_diffuse(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi);
// True when every lobe is a delta lobe (no light sampling is useful).
bool bsdf_is_delta(const Bsdf& bsdf);
// True when the BSDF transmits (dielectric): light may reach it from either side.
bool bsdf_transmits(const Bsdf& bsdf);
// The normal a surface vertex shades with, seen from wo_world: opaque BSDFs
// are two-sided (the normal turned toward wo_world); a dielectric keeps the
// geometric orientation (outside = the normal's side).
Vec3 bsdf_shading_normal(const Bsdf& bsdf, const Vec3& n, const Vec3& wo_world);
// Directional-hemispherical reflectance estimate for the `albedo` AOV.
Rgb bsdf_albedo(const Bsdf& bsdf);

}  // namespace vesper
