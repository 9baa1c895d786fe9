#include "renderer/bsdf/principled.h"

#include "renderer/bsdf/fresnel.h"
#include "renderer/bsdf/microfacet.h"
#include "renderer/math/constants.h"
#include "renderer/sampling/warp.h"

namespace vesper::bsdf_detail {
namespace {

void to_upper(Vec3& wo, Vec3& wi) {
  if (wo.z < 0.f) {
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
}

bool smooth_specular(const PrincipledBsdf& b) { return b.alpha < kSpecularAlpha; }
Rgb diffuse_color(const PrincipledBsdf& b) { return b.base_color * (1.f - b.metallic); }
Rgb specular_f0(const PrincipledBsdf& b) { return lerp(b.metallic, Rgb(0.04f), b.base_color); }

// Probability of sampling the specular lobe; depends on wo only (wo.z > 0).
float specular_probability(const PrincipledBsdf& b, const Vec3& wo) {
  const float diffuse = diffuse_color(b).average();
  if (!(diffuse > 0.f)) return 1.f;
  const float spec = fresnel_schlick(specular_f0(b), wo.z).average();
  return clamp(spec / (spec + diffuse), 0.1f, 0.9f);
}

// Burley diffuse with Frostbite's renormalisation, without the 1/pi and colour.
// cos_d^2 = (wo.wi + 1) / 2 is the squared cosine of the half angle, which
// needs no normalised half vector.
float burley(const PrincipledBsdf& b, const Vec3& wo, const Vec3& wi) {
  const float r = std::sqrt(std::max(0.f, b.alpha));
  const float bias = 0.5f * r;
  const float factor = 1.f + r * (1.f / 1.51f - 1.f);
  const float cos_d2 = clamp(0.5f * (dot(wo, wi) + 1.f), 0.f, 1.f);
  const float fd90 = bias + 2.f * r * cos_d2;
  const float light = 1.f + (fd90 - 1.f) * schlick_weight(wi.z);
  const float view = 1.f + (fd90 - 1.f) * schlick_weight(wo.z);
  return light * view * factor;
}

// Both lobes for wo, wi above the surface (the specular one only when rough).
Rgb eval_upper(const PrincipledBsdf& b, const Vec3& wo, const Vec3& wi) {
  if (!(wo.z > 0.f) || !(wi.z > 0.f)) return {};
  Rgb f = diffuse_color(b) * (burley(b, wo, wi) * kInvPi);
  if (smooth_specular(b)) return f;
  const Vec3 h = wo + wi;
  const float l2 = length_squared(h);
  if (!(l2 > 0.f)) return f;
  const Vec3 wm = h / std::sqrt(l2);
  const Ggx ggx{b.alpha};
  return f + fresnel_schlick(specular_f0(b), dot(wo, wm)) * (ggx.d(wm) * ggx.visibility(wo, wi));
}

// Mixture density for wo, wi above the surface.
float pdf_upper(const PrincipledBsdf& b, const Vec3& wo, const Vec3& wi) {
  if (!(wo.z > 0.f) || !(wi.z > 0.f)) return 0.f;
  const float p_spec = specular_probability(b, wo);
  float pdf = (1.f - p_spec) * wi.z * kInvPi;
  if (smooth_specular(b)) return pdf;
  const Vec3 h = wo + wi;
  const float l2 = length_squared(h);
  if (!(l2 > 0.f)) return pdf;
  const Vec3 wm = h / std::sqrt(l2);
  const float cos_om = dot(wo, wm);
  if (cos_om > 0.f) pdf += p_spec * Ggx{b.alpha}.vndf_pdf(wo, wm) / (4.f * cos_om);
  return std::isfinite(pdf) ? pdf : 0.f;
}

}  // namespace

Rgb eval(const PrincipledBsdf& b, Vec3 wo, Vec3 wi) {
  to_upper(wo, wi);
  return eval_upper(b, wo, wi);
}

float pdf(const PrincipledBsdf& b, Vec3 wo, Vec3 wi) {
  to_upper(wo, wi);
  return pdf_upper(b, wo, wi);
}

std::optional<BsdfSample> sample(const PrincipledBsdf& b, Vec3 wo, float uc, Vec2 u) {
  if (wo.z == 0.f) return std::nullopt;
  const bool flipped = wo.z < 0.f;
  if (flipped) wo.z = -wo.z;
  const float p_spec = specular_probability(b, wo);
  BsdfSample s;
  if (uc < p_spec && smooth_specular(b)) {
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.f = fresnel_schlick(specular_f0(b), wo.z) / wo.z;
    s.pdf = p_spec;
    s.is_specular = true;
  } else {
    if (uc < p_spec) {
      const Ggx ggx{b.alpha};
      s.wi = reflect(wo, ggx.sample_vndf(wo, u));
    } else {
      s.wi = sample_cosine_hemisphere(u);
    }
    if (!(s.wi.z > 0.f)) return std::nullopt;  // below the surface: absorbed
    s.f = eval_upper(b, wo, s.wi);
    s.pdf = pdf_upper(b, wo, s.wi);
    if (!(s.pdf > 0.f) || !std::isfinite(s.pdf) || !s.f.is_finite()) return std::nullopt;
  }
  if (flipped) s.wi.z = -s.wi.z;
  return s;
}

Rgb eval_diffuse(const PrincipledBsdf& b, Vec3 wo, Vec3 wi) {
  to_upper(wo, wi);
  if (!(wo.z > 0.f) || !(wi.z > 0.f)) return {};
  return diffuse_color(b) * (burley(b, wo, wi) * kInvPi);
}

Rgb albedo(const PrincipledBsdf& b) {
  const Rgb a = diffuse_color(b) * 0.96f + specular_f0(b);
  return {std::min(a.r, 1.f), std::min(a.g, 1.f), std::min(a.b, 1.f)};
}

bool is_delta(const PrincipledBsdf& b) { return smooth_specular(b) && diffuse_color(b).is_black(); }

}  // namespace vesper::bsdf_detail
