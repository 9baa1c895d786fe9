#pragma once
#include "renderer/math/vec.h"

namespace vesper {

// Where a light is chosen for: a surface point with the normal of its
// reflecting side, or (n = 0) a point in a medium or on a transmissive
// surface. The MIS weight of a BSDF ray that hits a light needs the pmf at
// the vertex the ray left, so paths keep this (integrator/path_context.h).
struct ShadingPoint {
  Vec3 p;
  Vec3 n;
};

}  // namespace vesper
