#include "renderer/core/camera.h"

#include "renderer/sampling/warp.h"

namespace vesper {

Ray Camera::generate_ray(float fx, float fy, Vec2 u_lens) const {
  const float sx = (2.f * fx / float(width) - 1.f) * tan_half_x;
  const float sy = (1.f - 2.f * fy / float(height)) * tan_half_y;
  Vec3 dir_cam{sx, sy, 1.f};  // camera space: x right, y up, z forward
  Vec3 origin_cam{0, 0, 0};
  if (lens_radius > 0.f) {
    const Vec2 d = sample_uniform_disk_concentric(u_lens);
    const Vec3 focus = dir_cam * focus_distance;
    origin_cam = {d.x * lens_radius, d.y * lens_radius, 0.f};
    dir_cam = focus - origin_cam;
  }
  Ray ray;
  ray.origin = position + right * origin_cam.x + up * origin_cam.y;
  ray.dir = normalize(right * dir_cam.x + up * dir_cam.y + forward * dir_cam.z);
  return ray;
}

}  // namespace vesper
