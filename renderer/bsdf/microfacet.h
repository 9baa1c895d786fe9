#pragma once
// Isotropic GGX (Trowbridge-Reitz) microfacet distribution with the Smith
// masking-shadowing terms (height-correlated G2) and visible-normal sampling
// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
//
// Directions are in the local frame (z = macro normal). Microfacet normals wm
// are in the upper hemisphere. Masking terms use |w.z| so they accept either
// side; sample_vndf/vndf_pdf expect the viewing direction mirrored into the
// upper hemisphere by the caller.
//
// Every term is written in a form that stays finite at grazing angles:
// with a(w) = sqrt(w.z^2 + alpha^2 (w.x^2 + w.y^2)), Lambda(w) = (a/|w.z| - 1)/2,
// so G1 = 2|w.z| / (|w.z| + a) and G2 = 2|zo||zi| / (a_o|zi| + a_i|zo|).
#include <cmath>

#include "renderer/math/constants.h"
#include "renderer/math/vec.h"

namespace vesper {

struct Ggx {
  float alpha = 1;

  // D(wm), normalised so that the projected microfacet area is 1:
  // integral of D(wm) wm.z over the hemisphere = 1. Written with sin^2
  // from x, y (not 1 - cos^2) to stay accurate for tiny alpha.
  float d(const Vec3& wm) const {
    if (wm.z <= 0.f) return 0.f;
    const float a2 = alpha * alpha;
    const float t = wm.x * wm.x + wm.y * wm.y + a2 * wm.z * wm.z;
    return t > 0.f ? a2 / (kPi * t * t) : 0.f;
  }

  // a(w) = |w.z| sqrt(1 + alpha^2 tan^2(theta)), the helper shared by Lambda, G1, G2.
  float a(const Vec3& w) const {
    return std::sqrt(w.z * w.z + alpha * alpha * (w.x * w.x + w.y * w.y));
  }
  float lambda(const Vec3& w) const {
    const float z = std::abs(w.z);
    return z > 0.f ? 0.5f * (a(w) / z - 1.f) : INFINITY;
  }
  float g1(const Vec3& w) const {
    const float z = std::abs(w.z), den = z + a(w);
    return den > 0.f ? 2.f * z / den : 0.f;
  }
  // Height-correlated masking-shadowing 1 / (1 + Lambda(wo) + Lambda(wi)).
  float g2(const Vec3& wo, const Vec3& wi) const {
    const float zo = std::abs(wo.z), zi = std::abs(wi.z);
    const float den = a(wo) * zi + a(wi) * zo;
    return den > 0.f ? 2.f * zo * zi / den : 0.f;
  }
  // G2 / (4 |cos_o| |cos_i|): the "visibility" form, finite at grazing angles.
  float visibility(const Vec3& wo, const Vec3& wi) const {
    const float den = a(wo) * std::abs(wi.z) + a(wi) * std::abs(wo.z);
    return den > 0.f ? 0.5f / den : 0.f;
  }

  // Density of visible normals D_w(wm) = G1(w) max(0, w.wm) D(wm) / |w.z|, w.z >= 0.
  float vndf_pdf(const Vec3& w, const Vec3& wm) const {
    const float cos_m = dot(w, wm);
    if (cos_m <= 0.f) return 0.f;
    const float den = std::abs(w.z) + a(w);  // G1/|w.z| = 2 / den
    return den > 0.f ? 2.f * cos_m * d(wm) / den : 0.f;
  }

  // Samples wm with density vndf_pdf(w, .) for w.z >= 0 (Heitz 2018, listing 1).
  Vec3 sample_vndf(const Vec3& w, Vec2 u) const {
    // Stretch the view so that the distribution becomes the hemisphere of alpha 1.
    Vec3 vh(alpha * w.x, alpha * w.y, w.z);
    const float lv = length(vh);
    vh = lv > 0.f ? vh / lv : Vec3(0.f, 0.f, 1.f);
    // Orthonormal basis around vh (T1 is arbitrary when vh is the pole).
    const float lensq = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = lensq > 0.f ? Vec3(-vh.y, vh.x, 0.f) / std::sqrt(lensq) : Vec3(1.f, 0.f, 0.f);
    const Vec3 t2 = cross(vh, t1);
    // Uniform disk, then warp its lower half onto the projected visible hemisphere.
    const float r = std::sqrt(u.x), phi = 2.f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    float p2 = r * std::sin(phi);
    const float s = 0.5f * (1.f + vh.z);
    p2 = (1.f - s) * safe_sqrt(1.f - p1 * p1) + s * p2;
    const Vec3 nh = p1 * t1 + p2 * t2 + safe_sqrt(1.f - p1 * p1 - p2 * p2) * vh;
    // Unstretch; the 1e-6 floor keeps wm strictly in the upper hemisphere.
    return normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
  }
};

}  // namespace vesper
