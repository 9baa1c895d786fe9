#pragma once
// Lambertian reflection: f = albedo / pi, cosine-weighted sampling.
// Opaque and two-sided: a wo below the surface is handled as its mirror
// image; wi must be on wo's side, else f = pdf = 0.
#include <optional>

#include "renderer/bsdf/bsdf.h"

namespace vesper::bsdf_detail {

Rgb eval(const DiffuseBsdf& b, Vec3 wo, Vec3 wi);
float pdf(const DiffuseBsdf& b, Vec3 wo, Vec3 wi);
std::optional<BsdfSample> sample(const DiffuseBsdf& b, Vec3 wo, float uc, Vec2 u);
inline Rgb albedo(const DiffuseBsdf& b) { return b.albedo; }
inline bool is_delta(const DiffuseBsdf&) { return false; }

}  // namespace vesper::bsdf_detail
