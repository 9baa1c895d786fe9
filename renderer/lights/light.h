#pragma once
// The closed set of lights, and the choice between them for light sampling.
#include <algorithm>
#include <cmath>
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

// Picks a light with probability half proportional to its power, half
// uniform. Power alone lets a dim fill light take few shadow rays from the
// key light, but it also starves small nearby lights (candles) next to a sun
// whose power is counted over the whole scene even when it only enters
// through a window; the uniform half bounds every light's share from below.
class LightSampler {
 public:
  LightSampler() = default;
  LightSampler(const std::vector<Light>& lights, float scene_radius) {
    if (lights.empty()) return;
    std::vector<float> power;
    power.reserve(lights.size());
    double total = 0;
    for (const auto& l : lights) {
      const float p = light_power(l, scene_radius);
      power.push_back(std::isfinite(p) && p > 0.f ? p : 0.f);
      total += power.back();
    }
    std::vector<float> w;
    w.reserve(lights.size());
    // Lights that emit nothing (switched off, zero area) get no samples.
    const size_t emitting =
        size_t(std::count_if(power.begin(), power.end(), [](float p) { return p > 0.f; }));
    for (float p : power)
      w.push_back(p > 0.f ? float(0.5 * p / total) + 0.5f / float(emitting) : 0.f);
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
