#include "renderer/bsdf/dielectric.h"

#include "renderer/bsdf/fresnel.h"
#include "renderer/bsdf/microfacet.h"

namespace vesper::bsdf_detail {
namespace {

// What eval and pdf share for a rough (wo, wi) pair.
struct Pair {
  Vec3 wm;         // generalised half vector, upper hemisphere
  float etap = 1;  // n_t / n_i for transmission, 1 for reflection
  bool reflection = true;
  float fresnel = 0;  // F(wo.wm)
};

// Generalised half vector (Walter et al. 2007, eq. 16); nullopt when
// degenerate or when wo or wi sees the back of the microfacet.
std::optional<Pair> make_pair(const DielectricBsdf& b, const Vec3& wo, const Vec3& wi) {
  const float co = wo.z, ci = wi.z;
  if (co == 0.f || ci == 0.f) return std::nullopt;
  Pair p;
  p.reflection = co * ci > 0.f;
  if (!p.reflection) p.etap = co > 0.f ? b.eta : 1.f / b.eta;
  Vec3 wm = wi * p.etap + wo;
  const float l2 = length_squared(wm);
  if (!(l2 > 0.f) || !std::isfinite(l2)) return std::nullopt;
  wm = wm / std::sqrt(l2);
  if (wm.z < 0.f) wm = -wm;
  if (!(dot(wm, wi) * ci > 0.f) || !(dot(wm, wo) * co > 0.f)) return std::nullopt;
  p.wm = wm;
  p.fresnel = fresnel_dielectric(dot(wo, wm), b.eta);
  return p;
}

// wo mirrored into the upper hemisphere, where the visible normals are defined.
Vec3 upper(const Vec3& w) { return w.z < 0.f ? -w : w; }

// (wi.wm + wo.wm / etap)^2, the refraction Jacobian's denominator.
float refraction_denom(const Vec3& wo, const Vec3& wi, const Vec3& wm, float etap) {
  return sqr(dot(wi, wm) + dot(wo, wm) / etap);
}

bool smooth(const DielectricBsdf& b) { return b.alpha < kSpecularAlpha || b.eta == 1.f; }

}  // namespace

Rgb eval(const DielectricBsdf& b, Vec3 wo, Vec3 wi) {
  if (smooth(b)) return {};
  const auto p = make_pair(b, wo, wi);
  if (!p) return {};
  const Ggx ggx{b.alpha};
  if (p->reflection) return Rgb(ggx.d(p->wm) * ggx.visibility(wo, wi) * p->fresnel);
  const float denom = refraction_denom(wo, wi, p->wm, p->etap);
  if (!(denom > 0.f)) return {};
  // G2 / (|cos_o| |cos_i|) = 4 * visibility.
  const float ft = ggx.d(p->wm) * (1.f - p->fresnel) * 4.f * ggx.visibility(wo, wi) *
                   std::abs(dot(wi, p->wm) * dot(wo, p->wm)) / denom;
  const float f = ft / sqr(p->etap);
  return std::isfinite(f) ? Rgb(f) : Rgb();
}

float pdf(const DielectricBsdf& b, Vec3 wo, Vec3 wi) {
  if (smooth(b)) return 0.f;
  const auto p = make_pair(b, wo, wi);
  if (!p) return 0.f;
  const Ggx ggx{b.alpha};
  const float d_wm = ggx.vndf_pdf(upper(wo), p->wm);
  float pdf = 0.f;
  if (p->reflection) {
    pdf = d_wm / (4.f * std::abs(dot(wo, p->wm))) * p->fresnel;
  } else {
    const float denom = refraction_denom(wo, wi, p->wm, p->etap);
    if (!(denom > 0.f)) return 0.f;
    pdf = d_wm * std::abs(dot(wi, p->wm)) / denom * (1.f - p->fresnel);
  }
  return std::isfinite(pdf) ? pdf : 0.f;
}

std::optional<BsdfSample> sample(const DielectricBsdf& b, Vec3 wo, float uc, Vec2 u) {
  if (wo.z == 0.f) return std::nullopt;
  BsdfSample s;
  if (smooth(b)) {
    const float r = fresnel_dielectric(wo.z, b.eta);
    if (uc < r) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.f = Rgb(r / std::abs(s.wi.z));
      s.pdf = r;
    } else {
      const auto t = refract(wo, Vec3(0.f, 0.f, 1.f), b.eta);
      if (!t || t->wt.z == 0.f) return std::nullopt;
      s.wi = t->wt;
      s.f = Rgb((1.f - r) / std::abs(s.wi.z) / sqr(t->etap));
      s.pdf = 1.f - r;
      s.is_transmission = true;
    }
    s.is_specular = true;
    return s;
  }

  const Ggx ggx{b.alpha};
  const Vec3 wm = ggx.sample_vndf(upper(wo), u);
  const float cos_om = dot(wo, wm);
  if (cos_om == 0.f) return std::nullopt;
  const float r = fresnel_dielectric(cos_om, b.eta);
  const float d_wm = ggx.vndf_pdf(upper(wo), wm);
  if (uc < r) {
    s.wi = reflect(wo, wm);
    if (!(s.wi.z * wo.z > 0.f)) return std::nullopt;  // reflected to the wrong side
    s.pdf = d_wm / (4.f * std::abs(cos_om)) * r;
    s.f = Rgb(ggx.d(wm) * ggx.visibility(wo, s.wi) * r);
  } else {
    const auto t = refract(wo, wm, b.eta);
    if (!t || !(t->wt.z * wo.z < 0.f)) return std::nullopt;
    s.wi = t->wt;
    const float denom = refraction_denom(wo, s.wi, wm, t->etap);
    if (!(denom > 0.f)) return std::nullopt;
    const float cos_im = std::abs(dot(s.wi, wm));
    s.pdf = d_wm * cos_im / denom * (1.f - r);
    s.f = Rgb(ggx.d(wm) * (1.f - r) * 4.f * ggx.visibility(wo, s.wi) * cos_im * std::abs(cos_om) /
              denom / sqr(t->etap));
    s.is_transmission = true;
  }
  if (!(s.pdf > 0.f) || !std::isfinite(s.pdf) || !s.f.is_finite()) return std::nullopt;
  return s;
}

}  // namespace vesper::bsdf_detail
