#pragma once
// The closed set of lights, and the power-proportional choice between them.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "renderer/lights/environment_light.h"
#include "renderer/lights/point_light.h"
#include "renderer/lights/quad_light.h"
#include "renderer/lights/spot_light.h"
#include "renderer/lights/sun_light.h"
#include "renderer/sampling/distribution.h"

namespace vesper {

using Light = std::variant<QuadLight, PointLight, SpotLight, SunLight, EnvironmentLight>;

inline std::optional<LightSample> sample_light(const Light& light, const Vec3& p, Vec2 u) {
  return std::visit(
      [&](const auto& l) -> std::optional<LightSample> {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, QuadLight>)
          return l.sample(p, u);
        else if constexpr (std::is_same_v<T, PointLight> || std::is_same_v<T, SpotLight>)
          return l.sample(p);
        else
          return l.sample(u);
      },
      light);
}

inline float light_power(const Light& light, float scene_radius) {
  return std::visit(
      [&](const auto& l) -> float {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, EnvironmentLight>)
          return l.power(scene_radius);
        else
          return l.power();
      },
      light);
}

// Picks a light with probability proportional to its power, so a dim fill
// light does not take half the shadow rays from the key light.
class LightSampler {
 public:
  LightSampler() = default;
  LightSampler(const std::vector<Light>& lights, float scene_radius) {
    if (lights.empty()) return;
    std::vector<float> w;
    w.reserve(lights.size());
    for (const auto& l : lights) w.push_back(light_power(l, scene_radius));
    dist_ = Distribution1D(std::move(w));
  }
  bool empty() const { return dist_.size() == 0; }
  size_t sample(float u, float* pmf, float* u_remapped) const {
    return dist_.sample_discrete(u, pmf, u_remapped);
  }
  float pmf(size_t light_index) const { return dist_.discrete_pmf(light_index); }

 private:
  Distribution1D dist_;
};

}  // namespace vesper
