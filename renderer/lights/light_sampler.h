#pragma once
// The choice of a light for next-event estimation.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "renderer/lights/light.h"
#include "renderer/lights/light_importance.h"
#include "renderer/lights/light_selection.h"
#include "renderer/lights/light_tree.h"
#include "renderer/lights/shading_point.h"
#include "renderer/math/constants.h"
#include "renderer/sampling/distribution.h"

namespace vesper {

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
// lights.
//
// Tree makes the finite lights' choice with a light tree instead
// (light_tree.h): O(log N) per choice and per pmf, a coarser estimate. The
// lights at infinity keep their base share as in Spatial. Spatial itself
// switches to the tree above kTreeThreshold finite lights (measured:
// bench/README.md, "Light tree"), so scenes with few lights render as before.
class LightSampler {
 public:
  static constexpr float kFloor = 0.1f;
  static constexpr size_t kTreeThreshold = 64;

  // What a spatial choice at a point sums over all lights. Next-event
  // estimation keeps it so that the MIS weight of a light that the vertex's
  // BSDF or phase ray then hits costs one importance, not all of them again.
  struct Sums {
    float importance = 0.f;  // of the finite lights
    int reaching = 0;        // finite lights that may reach the point
    float total = 0.f;       // of all weights
  };

  LightSampler() = default;
  // `tree_threshold`: Spatial's switch to the tree (benches force either side).
  LightSampler(const std::vector<Light>& lights, float scene_radius,
               LightSelection mode = LightSelection::Spatial,
               size_t tree_threshold = kTreeThreshold)
      : mode_(mode) {
    if (lights.empty()) return;
    for (const auto& l : lights) {
      const float p = l.power(scene_radius);
      power_.push_back(std::isfinite(p) && p > 0.f ? p : 0.f);
      bounds_.push_back(l.bounds());
    }
    std::vector<float> w = base_weights(mode);
    // Equiangular sampling can only aim at lights that are one point (or a
    // sphere around one): Spatial and Tree pick among those alone, by the
    // same weights; PowerUniform keeps the choice among all lights it had
    // before (issue 11's start, which wasted the picks of the others).
    std::vector<float> aimable(w);
    if (mode != LightSelection::PowerUniform)
      for (size_t i = 0; i < aimable.size(); ++i)
        if (!bounds_[i] || !bounds_[i]->aim()) aimable[i] = 0.f;
    dist_ = Distribution1D(std::move(w));
    if (std::any_of(aimable.begin(), aimable.end(), [](float a) { return a > 0.f; }))
      aimable_ = Distribution1D(std::move(aimable));
    for (size_t i = 0; i < power_.size(); ++i)
      if (bounds_[i] && power_[i] > 0.f) finite_share_ += dist_.discrete_pmf(i);
    const size_t finite = size_t(
        std::count_if(bounds_.begin(), bounds_.end(), [](const auto& b) { return b.has_value(); }));
    if (mode == LightSelection::Tree ||
        (mode == LightSelection::Spatial && finite > tree_threshold))
      build_tree();
  }
  bool empty() const { return dist_.size() == 0; }
  LightSelection mode() const { return mode_; }
  // Whether the finite lights are chosen with the light tree (Tree, or
  // Spatial with many lights).
  bool uses_tree() const { return uses_tree_; }

  // The base choice, the same everywhere.
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
    if (uses_tree_) {
      if (sums_out) *sums_out = Sums{};
      return sample_tree(at, u, pmf, u_remapped);
    }
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
    if (uses_tree_) return pmf_tree(at, light_index);
    return pmf(at, light_index, sums(importances(at)));
  }
  // The same with the sums sample(at, ...) gave at `at`: one importance.
  // (The tree keeps no sums: its pmf is one walk down to the light.)
  float pmf(const ShadingPoint& at, size_t light_index, const Sums& s) const {
    if (mode_ == LightSelection::PowerUniform) return pmf(light_index);
    if (uses_tree_) return pmf_tree(at, light_index);
    return s.total > 0.f ? weight(light_index, importance(light_index, at), s) / s.total : 0.f;
  }

 private:
  // Half by power, half uniform. Lights that emit nothing (switched off,
  // zero area) get no samples. Spatial and Tree spread the uniform half
  // over the finite lights only, where there are any: it protects lights that
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
    const bool finite_only = mode != LightSelection::PowerUniform && finite > 0;
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
  void build_tree() {
    std::vector<LightTree::Item> items;
    std::vector<float> infinite_weights;
    for (size_t i = 0; i < power_.size(); ++i) {
      if (bounds_[i] && power_[i] > 0.f) items.push_back({i, *bounds_[i], power_[i]});
      if (!bounds_[i]) {
        infinite_.push_back(i);
        infinite_weights.push_back(dist_.discrete_pmf(i));
        infinite_share_ += dist_.discrete_pmf(i);
      }
    }
    tree_ = LightTree(std::move(items), power_.size());
    infinite_dist_ = Distribution1D(std::move(infinite_weights));
    uses_tree_ = true;
  }
  // The finite lights' share at `at`: all of theirs, or none when the tree
  // proves that none reaches it.
  float tree_share(const ShadingPoint& at) const { return tree_.reaches(at) ? finite_share_ : 0.f; }
  size_t sample_tree(const ShadingPoint& at, float u, float* pmf, float* u_remapped) const {
    const float finite = tree_share(at), total = finite + infinite_share_;
    const float target = u * total;
    if (finite > 0.f && (target < finite || infinite_.empty())) {
      const LightTree::Choice c =
          tree_.sample_reaching(at, std::min(target / finite, kOneMinusEpsilon));
      *pmf = c.pmf * (finite / total);
      *u_remapped = c.u_rest;
      return c.light;
    }
    if (infinite_.empty() || !(infinite_share_ > 0.f)) return pick(0, 0.f, 0.f, u, pmf, u_remapped);
    const size_t i = infinite_[infinite_dist_.sample_discrete(
        std::min((target - finite) / infinite_share_, kOneMinusEpsilon), nullptr, u_remapped)];
    *pmf = dist_.discrete_pmf(i) / total;
    return i;
  }
  float pmf_tree(const ShadingPoint& at, size_t i) const {
    const float finite = tree_share(at), total = finite + infinite_share_;
    if (!(total > 0.f)) return 0.f;
    if (!bounds_[i]) return dist_.discrete_pmf(i) / total;
    return finite > 0.f ? tree_.pmf_reaching(at, i) * (finite / total) : 0.f;
  }
  static size_t pick(size_t i, float w, float total, float u_rest, float* pmf, float* u_remapped) {
    *pmf = total > 0.f ? w / total : 0.f;
    *u_remapped = std::min(u_rest, kOneMinusEpsilon);
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
  // With the tree: the lights at infinity (indices) and their base choice.
  bool uses_tree_ = false;
  LightTree tree_;
  std::vector<size_t> infinite_;
  float infinite_share_ = 0.f;
  Distribution1D infinite_dist_;
};

}  // namespace vesper
