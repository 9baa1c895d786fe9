#include "renderer/bsdf/bsdf.h"

#include "renderer/bsdf/conductor.h"
#include "renderer/bsdf/dielectric.h"
#include "renderer/bsdf/diffuse.h"
#include "renderer/bsdf/principled.h"

// Closed-set dispatch: each alternative's functions live in its own header.
namespace vesper {

Rgb bsdf_eval(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi) {
  return std::visit([&](const auto& b) { return bsdf_detail::eval(b, wo, wi); }, bsdf);
}

float bsdf_pdf(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi) {
  return std::visit([&](const auto& b) { return bsdf_detail::pdf(b, wo, wi); }, bsdf);
}

std::optional<BsdfSample> bsdf_sample(const Bsdf& bsdf, const Vec3& wo, float uc, const Vec2& u) {
  return std::visit([&](const auto& b) { return bsdf_detail::sample(b, wo, uc, u); }, bsdf);
}

Rgb bsdf_eval_diffuse(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi) {
  return std::visit(
      [&](const auto& b) -> Rgb {
        using T = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<T, DiffuseBsdf>)
          return bsdf_detail::eval(b, wo, wi);
        else if constexpr (std::is_same_v<T, PrincipledBsdf>)
          return bsdf_detail::eval_diffuse(b, wo, wi);
        else
          return Rgb{};
      },
      bsdf);
}

bool bsdf_is_delta(const Bsdf& bsdf) {
  return std::visit([](const auto& b) { return bsdf_detail::is_delta(b); }, bsdf);
}

bool bsdf_transmits(const Bsdf& bsdf) { return std::holds_alternative<DielectricBsdf>(bsdf); }

Vec3 bsdf_shading_normal(const Bsdf& bsdf, const Vec3& n, const Vec3& wo_world) {
  return (!bsdf_transmits(bsdf) && dot(n, wo_world) < 0.f) ? -n : n;
}

Rgb bsdf_albedo(const Bsdf& bsdf) {
  return std::visit([](const auto& b) { return bsdf_detail::albedo(b); }, bsdf);
}

}  // namespace vesper
