#pragma once
// A bounding volume hierarchy over the finite lights, for next-event
// estimation with many lights (Conty & Kulla 2018; pbrt-v4's
// BVHLightSampler). Each node bounds its lights' boxes, emission cones and
// total power, so a choice walks from the root to one light, taking a child
// with probability by its importance at the shading point
// (light_importance.h): O(log N) per choice and per pmf, where weighing
// every light (light_sampler.h's linear spatial choice) is O(N).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "renderer/lights/light_bounds.h"
#include "renderer/lights/shading_point.h"

namespace vesper {

class LightTree {
 public:
  // The share of each choice made by a second walk that weighs the children
  // by how many lights they hold rather than by importance (light_tree.cpp).
  static constexpr float kFloor = 0.1f;

  // A finite light that emits: its index among the scene's lights.
  struct Item {
    size_t light = 0;
    LightBounds bounds;
    float power = 0;  // > 0
  };
  struct Choice {
    size_t light = 0;
    float pmf = 0;  // 0: the walk proved that no light below may reach the point
    float u_rest = 0;
  };

  LightTree() = default;
  // `light_count`: how many lights the scene has (the items' indices are below it).
  LightTree(std::vector<Item> items, size_t light_count);

  bool empty() const { return nodes_.empty(); }
  size_t depth() const { return depth_; }
  // False when the root's bounds prove that no light may reach `at`.
  bool reaches(const ShadingPoint& at) const;
  // A light for `at`, u uniform in [0, 1); pmf is exactly pmf(at, light).
  Choice sample(const ShadingPoint& at, float u) const;
  // The probability that sample(at, .) picks `light`: one walk down its
  // trail. 0 for lights that are not in the tree.
  float pmf(const ShadingPoint& at, size_t light) const;
  // The same where the caller already knows reaches(at) (LightSampler tests
  // it once to split its choice): the root's importance is not taken again.
  Choice sample_reaching(const ShadingPoint& at, float u) const;
  float pmf_reaching(const ShadingPoint& at, size_t light) const;

 private:
  struct Node {
    LightBounds bounds;  // of every light below
    float power = 0;     // their sum
    uint32_t count = 0;  // lights below
    // Inner node: the second child's index (the first follows the node);
    // leaf: the light's index among the scene's lights.
    size_t second_or_light = 0;
    bool leaf = false;
  };
  // How a walk leaves an inner node: the first child's probability by
  // importance and by count.
  struct Odds {
    float by_importance = 0, by_count = 0;
  };
  // Root to leaf: bit d set = the second child at depth d.
  struct Trail {
    uint64_t bits = 0;
    int depth = -1;  // -1: not in the tree
  };

  size_t build(std::vector<Item>& items, size_t begin, size_t end, uint64_t bits, int depth);
  // A node's importance at a point with its power at its box's centre and
  // at its nearest point (light_tree.cpp); a leaf's is its light's, twice.
  struct Importance {
    float centre = 0, nearest = 0;
  };
  std::optional<Importance> importance(const Node& node, const ShadingPoint& at) const;
  std::optional<Odds> odds(size_t inner, const ShadingPoint& at) const;

  std::vector<Node> nodes_;  // depth first, the root at 0
  std::vector<Trail> trails_;
  size_t depth_ = 0;
};

// The bounds of two lights together: the union of their boxes and a cone
// holding both emission cones (conservative, so a zero importance of the
// merged bounds still proves that neither light reaches a point).
LightBounds merge_light_bounds(const LightBounds& a, const LightBounds& b);

}  // namespace vesper
