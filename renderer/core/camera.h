#pragma once
// Thin-lens perspective camera in render space (camera-relative, unit scale).
#include <vector>

#include "renderer/core/ray.h"
#include "renderer/math/frame.h"

namespace vesper {

struct Camera {
  Vec3 position;
  Vec3 right, up, forward;  // image right = normalize(cross(forward, up))
  float tan_half_x = 1, tan_half_y = 1;
  float lens_radius = 0;
  float focus_distance = 1;
  int width = 1, height = 1;

  // (fx, fy) are continuous raster coordinates: x right, y down, pixel (i, j)
  // covers [i, i+1) x [j, j+1). u_lens samples the aperture.
  Ray generate_ray(float fx, float fy, Vec2 u_lens) const;
};

// Motion blur: the camera at shutter time `time` in [0, 1] from its K >= 2
// steps (core/motion_steps.h): position, axes, field of view and lens
// interpolated linearly, the axes then made orthonormal again.
Camera camera_at(const std::vector<Camera>& steps, float time);

}  // namespace vesper
