#pragma once
// The choice of a light for next-event estimation.
#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/lights/light.h"
#include "renderer/sampling/distribution.h"

namespace vesper {

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
      const float p = l.power(scene_radius);
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
