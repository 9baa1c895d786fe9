#pragma once
#include <limits>

#include "renderer/math/vec.h"

namespace vesper {

struct Ray {
  Vec3 origin;
  Vec3 dir;  // unit length
  float tmax = std::numeric_limits<float>::infinity();
  // The instant the ray lives at, as a fraction of the shutter in [0, 1]
  // (motion blur: Embree's ray time). A path keeps its camera ray's time for
  // every bounce and shadow ray; 0 in a still scene, where nothing reads it.
  float time = 0;
};

// Moves p off the surface along the geometric normal n (facing the side the
// new ray leaves from) by a few float ulps of p. Wächter & Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6. The
// scene is rescaled to unit size before rendering, so the constants below
// hold for any scene scale.
Vec3 offset_ray_origin(const Vec3& p, const Vec3& n);

}  // namespace vesper
