#pragma once
#include "renderer/math/rgb.h"
#include "renderer/math/vec.h"

namespace vesper {

// A direction toward a light from a reference point.
struct LightSample {
  Rgb radiance;        // incident radiance (delta lights: intensity/d^2 or irradiance)
  Vec3 wi;             // unit direction from the reference point toward the light
  float distance = 0;  // to the light point; infinity for lights at infinity
  float pdf = 0;       // solid-angle density; 1 for delta lights
  bool is_delta = false;
};

}  // namespace vesper
