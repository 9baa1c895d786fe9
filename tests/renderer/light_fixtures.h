#pragma once
// Lights built in code for the light-selection tests.
#include <cmath>

#include "renderer/lights/light.h"
#include "renderer/math/constants.h"

namespace vesper::test {

// A quad light corner + a e1 + b e2, emitting toward cross(e1, e2).
inline QuadLight make_quad(Vec3 corner, Vec3 e1, Vec3 e2, float radiance) {
  QuadLight q;
  q.corner = corner;
  q.edge1 = e1;
  q.edge2 = e2;
  const Vec3 c = cross(e1, e2);
  q.area = length(c);
  q.normal = c / q.area;
  q.radiance = Rgb(radiance);
  return q;
}

// A spot light at p shining along unit `axis`, cone_angle and falloff_start in degrees.
inline SpotLight make_spot(Vec3 p, Vec3 axis, float intensity, float cone_angle,
                           float falloff_start, float radius = 0.f) {
  SpotLight s;
  s.position = p;
  s.direction = normalize(axis);
  s.intensity = Rgb(intensity);
  s.cos_cone = std::cos(radians(cone_angle));
  s.cos_falloff_start = std::cos(radians(falloff_start));
  s.radius = radius;
  return s;
}

}  // namespace vesper::test
