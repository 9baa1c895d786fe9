#pragma once
#include <optional>

#include "renderer/math/vec.h"

namespace vesper {

// The render-space box a light occupies (pbrt-v4's LightBounds, without the
// emission cone). Lights at infinity have none. A point or spot light's box
// is its position alone; a sphere light's the sphere's box. Equiangular
// sampling aims at either's centre (`aim`).
struct LightBounds {
  Vec3 lo, hi;
  bool sphere = false;  // a sphere light (its samples are delta-like too)

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
