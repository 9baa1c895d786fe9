#pragma once
// Frostbite/Disney "principled" BSDF (opaque, two-sided):
//   f = (1 - metallic) base_color * Fd / pi  +  F_schlick(wo.wm) D G2 / (4 cos_o cos_i)
// with F0 = lerp(metallic, 0.04, base_color) and GGX alpha from bsdf.h.
// Fd is Burley's (Disney 2012) retro-reflective diffuse term with Frostbite's
// energy renormalisation (Lagarde & de Rousiers 2014): fd90 = bias + 2 r cos_d^2,
// times a factor going from 1 (r = 0) to 1/1.51 (r = 1), r = sqrt(alpha) the
// perceptual roughness. It is reciprocal. Like Disney's model the specular lobe
// is added on top of the diffuse one without coupling, so the sum is not
// exactly energy conserving for white base colours at grazing angles (about
// +6% at cos_o = 0.03 and roughness 1, see bsdf_test WhiteFurnace).
//
// Sampling: the specular lobe (visible normals) with probability p_spec, a
// Fresnel-weighted estimate from wo alone, clamped to [0.1, 0.9] (1 when the
// diffuse lobe is black); the cosine-weighted diffuse lobe otherwise. Samples
// carry the full f of both lobes and the mixture pdf (one-sample MIS), equal
// to bsdf_eval/bsdf_pdf.
// alpha < kSpecularAlpha: the specular lobe is a delta mirror. Picking it
// gives an is_specular sample with f = F / cos_i and pdf = p_spec; eval and
// pdf then hold only the diffuse lobe, pdf = (1 - p_spec) cos_i / pi.
#include <optional>

#include "renderer/bsdf/bsdf.h"

namespace vesper::bsdf_detail {

Rgb eval(const PrincipledBsdf& b, Vec3 wo, Vec3 wi);
float pdf(const PrincipledBsdf& b, Vec3 wo, Vec3 wi);
std::optional<BsdfSample> sample(const PrincipledBsdf& b, Vec3 wo, float uc, Vec2 u);
// Diffuse albedo plus normal-incidence specular reflectance, clamped to 1.
Rgb albedo(const PrincipledBsdf& b);
// The Burley diffuse lobe alone (part of eval).
Rgb eval_diffuse(const PrincipledBsdf& b, Vec3 wo, Vec3 wi);
// Only when the specular lobe is a delta and the diffuse lobe is black.
bool is_delta(const PrincipledBsdf& b);

}  // namespace vesper::bsdf_detail
