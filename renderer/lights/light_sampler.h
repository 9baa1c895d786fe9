#pragma once
// The choice of a light for next-event estimation.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "renderer/lights/light.h"
#include "renderer/lights/light_importance.h"
#include "renderer/lights/light_selection.h"
#include "renderer/sampling/distribution.h"

namespace vesper {

// Where a light is chosen for: a surface point with the normal of its
// reflecting side, or (n = 0) a point in a medium or on a transmissive
// surface. The MIS weight of a BSDF ray that hits a light needs the pmf at
// the vertex the ray left, so paths keep this (integrator/path_context.h).
struct ShadingPoint {
  Vec3 p;
  Vec3 n;
};

// PowerUniform picks a light with probability half proportional to its
// power, half uniform ("base"). Power alone lets a dim fill light take few
// shadow rays from the key light, but it also starves small nearby lights
// (candles) next to a sun whose power is counted over the whole scene even
// when it only enters through a window; the uniform half bounds every light's
// share from below (base_weights says where Spatial spreads it).
//
// Spatial keeps the lights at infinity at their base share and splits the
// finite lights' base share by their importance at the shading point
// (light_importance.h): (1 - kFloor) by importance, kFloor evenly over every
// finite light that may reach the point, so an occluded bright neighbour
// cannot starve the others. One O(N) pass per choice: fine for tens of
// lights; many lights want a light tree (future work).
class LightSampler {
 public:
  static constexpr float kFloor = 0.1f;

  // What a spatial choice at a point sums over all lights. Next-event
  // estimation keeps it so that the MIS weight of a light that the vertex's
  // BSDF or phase ray then hits costs one importance, not all of them again.
  struct Sums {
    float importance = 0.f;  // of the finite lights
    int reaching = 0;        // finite lights that may reach the point
    float total = 0.f;       // of all weights
  };

  LightSampler() = default;
  LightSampler(const std::vector<Light>& lights, float scene_radius,
               LightSelection mode = LightSelection::Spatial)
      : mode_(mode) {
    if (lights.empty()) return;
    for (const auto& l : lights) {
      const float p = l.power(scene_radius);
      power_.push_back(std::isfinite(p) && p > 0.f ? p : 0.f);
      bounds_.push_back(l.bounds());
    }
    std::vector<float> w = base_weights(mode);
    // Equiangular sampling can only aim at lights that are one point (or a
    // sphere around one): Spatial picks among those alone, by the same
    // weights; PowerUniform keeps the choice among all lights it had before
    // (issue 11's starting point, which wasted the picks of the others).
    std::vector<float> aimable(w);
    if (mode == LightSelection::Spatial)
      for (size_t i = 0; i < aimable.size(); ++i)
        if (!bounds_[i] || !bounds_[i]->aim()) aimable[i] = 0.f;
    dist_ = Distribution1D(std::move(w));
    if (std::any_of(aimable.begin(), aimable.end(), [](float a) { return a > 0.f; }))
      aimable_ = Distribution1D(std::move(aimable));
    for (size_t i = 0; i < power_.size(); ++i)
      if (bounds_[i] && power_[i] > 0.f) finite_share_ += dist_.discrete_pmf(i);
  }
  bool empty() const { return dist_.size() == 0; }
  LightSelection mode() const { return mode_; }

  // The base choice, the same everywhere (equiangular sampling, which picks
  // a light for a whole ray).
  size_t sample(float u, float* pmf, float* u_remapped) const {
    return dist_.sample_discrete(u, pmf, u_remapped);
  }
  float pmf(size_t light_index) const { return dist_.discrete_pmf(light_index); }
  // Equiangular sampling's choice: among the lights it can aim at (point and
  // spot lights, with or without a radius); none when there are none.
  bool has_aimable() const { return aimable_.size() > 0; }
  size_t sample_aimable(float u, float* pmf, float* u_remapped) const {
    return aimable_.sample_discrete(u, pmf, u_remapped);
  }
  float pmf_aimable(size_t light_index) const {
    return has_aimable() ? aimable_.discrete_pmf(light_index) : 0.f;
  }
  // What the lights are, for strategies that start at them (light_vertex.h).
  const std::vector<float>& powers() const { return power_; }
  const std::vector<std::optional<LightBounds>>& bounds() const { return bounds_; }

  // The choice at a shading point; `pmf` is exactly pmf(at, index).
  // `sums_out` (optional) receives the sums for pmf(at, i, sums) later.
  size_t sample(const ShadingPoint& at, float u, float* pmf, float* u_remapped,
                Sums* sums_out = nullptr) const {
    if (mode_ == LightSelection::PowerUniform) return sample(u, pmf, u_remapped);
    const std::vector<float>& imp = importances(at);
    const Sums s = sums(imp);
    if (sums_out) *sums_out = s;
    const float target = u * s.total;
    float cum = 0.f;
    size_t last = 0;
    for (size_t i = 0; i < power_.size(); ++i) {
      const float w = weight(i, imp[i], s);
      if (!(w > 0.f)) continue;
      last = i;
      if (target < cum + w) return pick(i, w, s.total, (target - cum) / w, pmf, u_remapped);
      cum += w;
    }
    // Rounding left u past the last weight: the last light that has one.
    const float w = s.total > 0.f ? weight(last, imp[last], s) : 0.f;
    return pick(last, w, s.total, 1.f, pmf, u_remapped);
  }
  float pmf(const ShadingPoint& at, size_t light_index) const {
    if (mode_ == LightSelection::PowerUniform) return pmf(light_index);
    return pmf(at, light_index, sums(importances(at)));
  }
  // The same with the sums sample(at, ...) gave at `at`: one importance.
  float pmf(const ShadingPoint& at, size_t light_index, const Sums& s) const {
    if (mode_ == LightSelection::PowerUniform) return pmf(light_index);
    return s.total > 0.f ? weight(light_index, importance(light_index, at), s) / s.total : 0.f;
  }

 private:
  // Half by power, half uniform. Lights that emit nothing (switched off,
  // zero area) get no samples. Spatial spreads the uniform half over the
  // finite lights only, where there are any: it protects small lights that
  // are bright up close (a candle beside a sun), and lights at infinity are
  // never close; a dim sky then stops taking half the shadow rays
  // (fog-shafts: 56 % of them before). PowerUniform spreads it over all.
  std::vector<float> base_weights(LightSelection mode) const {
    double total = 0;
    size_t emitting = 0, finite = 0;
    for (size_t i = 0; i < power_.size(); ++i) {
      total += power_[i];
      emitting += power_[i] > 0.f;
      finite += power_[i] > 0.f && bounds_[i].has_value();
    }
    const bool finite_only = mode == LightSelection::Spatial && finite > 0;
    const float uniform = 0.5f / float(finite_only ? finite : emitting);
    std::vector<float> w;
    w.reserve(power_.size());
    for (size_t i = 0; i < power_.size(); ++i) {
      const bool emits = power_[i] > 0.f;
      const bool takes_uniform = emits && (!finite_only || bounds_[i].has_value());
      w.push_back(emits ? float(0.5 * power_[i] / total) + (takes_uniform ? uniform : 0.f) : 0.f);
    }
    return w;
  }
  static size_t pick(size_t i, float w, float total, float u_rest, float* pmf, float* u_remapped) {
    *pmf = total > 0.f ? w / total : 0.f;
    *u_remapped = std::min(u_rest, 0x1.fffffep-1f);
    return i;
  }
  // Each finite light's importance at `at`, -1 where it provably gives
  // nothing (or is at infinity), in a per-thread scratch: one evaluation per
  // light and choice, no allocation once warm.
  const std::vector<float>& importances(const ShadingPoint& at) const {
    thread_local std::vector<float> imp;
    imp.resize(power_.size());
    for (size_t i = 0; i < power_.size(); ++i) imp[i] = importance(i, at);
    return imp;
  }
  float importance(size_t i, const ShadingPoint& at) const {
    if (!bounds_[i] || !(power_[i] > 0.f)) return -1.f;
    return light_importance(*bounds_[i], power_[i], at.p, at.n).value_or(-1.f);
  }
  Sums sums(const std::vector<float>& imp) const {
    Sums s;
    for (size_t i = 0; i < power_.size(); ++i)
      if (bounds_[i] && imp[i] >= 0.f) {
        s.importance += imp[i];
        ++s.reaching;
      }
    for (size_t i = 0; i < power_.size(); ++i) s.total += weight(i, imp[i], s);
    return s;
  }
  // Unnormalised weight of light i with importance `imp`, given the sums.
  float weight(size_t i, float imp, const Sums& s) const {
    if (!bounds_[i]) return dist_.discrete_pmf(i);
    if (!(imp >= 0.f) || s.reaching == 0) return 0.f;
    const float by_importance = s.importance > 0.f ? imp / s.importance : 1.f / float(s.reaching);
    return finite_share_ * ((1.f - kFloor) * by_importance + kFloor / float(s.reaching));
  }

  LightSelection mode_ = LightSelection::Spatial;
  std::vector<float> power_;
  std::vector<std::optional<LightBounds>> bounds_;
  float finite_share_ = 0.f;  // base probability of all finite lights together
  Distribution1D dist_;
  Distribution1D aimable_;
};

}  // namespace vesper
