#include "renderer/bsdf/conductor.h"

#include "renderer/bsdf/fresnel.h"
#include "renderer/bsdf/microfacet.h"

namespace vesper::bsdf_detail {
namespace {

// Two-sided: mirror both directions so that wo is above the surface.
void to_upper(Vec3& wo, Vec3& wi) {
  if (wo.z < 0.f) {
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
}

// Half vector of a reflection pair with both directions above the surface;
// nullopt when degenerate.
std::optional<Vec3> half_vector(const Vec3& wo, const Vec3& wi) {
  if (wo.z <= 0.f || wi.z <= 0.f) return std::nullopt;
  const Vec3 h = wo + wi;
  const float l2 = length_squared(h);
  if (!(l2 > 0.f)) return std::nullopt;
  return h / std::sqrt(l2);
}

}  // namespace

Rgb eval(const ConductorBsdf& b, Vec3 wo, Vec3 wi) {
  if (b.alpha < kSpecularAlpha) return {};
  to_upper(wo, wi);
  const auto wm = half_vector(wo, wi);
  if (!wm) return {};
  const Ggx ggx{b.alpha};
  return fresnel_complex(dot(wo, *wm), b.eta, b.k) * (ggx.d(*wm) * ggx.visibility(wo, wi));
}

float pdf(const ConductorBsdf& b, Vec3 wo, Vec3 wi) {
  if (b.alpha < kSpecularAlpha) return 0.f;
  to_upper(wo, wi);
  const auto wm = half_vector(wo, wi);
  if (!wm) return 0.f;
  const float cos_om = dot(wo, *wm);
  if (!(cos_om > 0.f)) return 0.f;
  // Reflection Jacobian d(wm)/d(wi) = 1 / (4 wo.wm).
  return Ggx{b.alpha}.vndf_pdf(wo, *wm) / (4.f * cos_om);
}

std::optional<BsdfSample> sample(const ConductorBsdf& b, Vec3 wo, float, Vec2 u) {
  if (wo.z == 0.f) return std::nullopt;
  const bool flipped = wo.z < 0.f;
  if (flipped) wo.z = -wo.z;
  BsdfSample s;
  if (b.alpha < kSpecularAlpha) {
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.f = fresnel_complex(wo.z, b.eta, b.k) / wo.z;
    s.pdf = 1.f;
    s.is_specular = true;
  } else {
    const Ggx ggx{b.alpha};
    const Vec3 wm = ggx.sample_vndf(wo, u);
    const float cos_om = dot(wo, wm);
    s.wi = reflect(wo, wm);
    if (!(cos_om > 0.f) || !(s.wi.z > 0.f)) return std::nullopt;  // below: absorbed
    s.pdf = ggx.vndf_pdf(wo, wm) / (4.f * cos_om);
    if (!(s.pdf > 0.f) || !std::isfinite(s.pdf)) return std::nullopt;
    s.f = fresnel_complex(cos_om, b.eta, b.k) * (ggx.d(wm) * ggx.visibility(wo, s.wi));
  }
  if (flipped) s.wi.z = -s.wi.z;
  return s;
}

Rgb albedo(const ConductorBsdf& b) { return fresnel_complex(1.f, b.eta, b.k); }

}  // namespace vesper::bsdf_detail
