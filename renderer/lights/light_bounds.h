#pragma once
#include "renderer/math/vec.h"

namespace vesper {

// The render-space box a light occupies (pbrt-v4's LightBounds, without the
// emission cone). Lights at infinity have none. A point or spot light's box
// is its position alone, which is what equiangular sampling aims at.
struct LightBounds {
  Vec3 lo, hi;

  bool is_point() const { return lo == hi; }
};

}  // namespace vesper
