#include "renderer/bsdf/diffuse.h"

#include "renderer/math/constants.h"
#include "renderer/sampling/warp.h"

namespace vesper::bsdf_detail {

Rgb eval(const DiffuseBsdf& b, Vec3 wo, Vec3 wi) {
  if (wo.z * wi.z <= 0.f) return {};
  return b.albedo * kInvPi;
}

float pdf(const DiffuseBsdf&, Vec3 wo, Vec3 wi) {
  if (wo.z * wi.z <= 0.f) return 0.f;
  return std::abs(wi.z) * kInvPi;
}

std::optional<BsdfSample> sample(const DiffuseBsdf& b, Vec3 wo, float, Vec2 u) {
  if (wo.z == 0.f) return std::nullopt;
  Vec3 wi = sample_cosine_hemisphere(u);
  // The disk's rim maps to wi.z == 0, where pdf() is 0: not a valid sample.
  if (wi.z <= 0.f) return std::nullopt;
  if (wo.z < 0.f) wi.z = -wi.z;
  return BsdfSample{b.albedo * kInvPi, wi, std::abs(wi.z) * kInvPi, false, false};
}

}  // namespace vesper::bsdf_detail
