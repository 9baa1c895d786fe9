#pragma once
// Isotropic point light; `intensity` is radiant intensity (W/sr).
#include <cmath>
#include <optional>

#include "renderer/lights/light_sample.h"
#include "renderer/math/constants.h"

namespace vesper {

struct PointLight {
  Vec3 position;
  Rgb intensity;

  std::optional<LightSample> sample(const Vec3& p) const {
    const Vec3 d = position - p;
    const float dist2 = length_squared(d);
    if (!(dist2 > 0.f)) return std::nullopt;
    const float dist = std::sqrt(dist2);
    return LightSample{intensity / dist2, d / dist, dist, 1.f, true};
  }
  float power() const { return 4.f * kPi * intensity.average(); }
};

}  // namespace vesper
