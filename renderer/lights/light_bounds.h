#pragma once
#include <optional>

#include "renderer/math/vec.h"

namespace vesper {

// The render-space box a light occupies (pbrt-v4's LightBounds, with a
// simpler emission cone). Lights at infinity have none. A point or spot light's box
// is its position alone; a sphere light's the sphere's box. Equiangular
// sampling aims at either's centre (`aim`).
struct LightBounds {
  Vec3 lo, hi;
  bool sphere = false;  // a sphere light (its samples are delta-like too)
  // Emission cone: the light leaves the box only in directions within
  // acos(cos_cone) of `axis` (a quad: its normal's hemisphere; a spot: its
  // cone); cos_cone = -1 emits everywhere. `cosine`: the radiance seen from
  // a direction falls with its cosine to the axis (a quad), not a spot's.
  Vec3 axis{};
  float cos_cone = -1.f;
  bool cosine = false;

  bool is_point() const { return lo == hi; }
  // The point equiangular sampling aims at: a point light's position or a
  // sphere light's centre; none for other lights.
  std::optional<Vec3> aim() const {
    if (is_point()) return lo;
    if (sphere) return (lo + hi) * 0.5f;
    return std::nullopt;
  }
};

}  // namespace vesper
