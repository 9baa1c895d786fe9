#include "renderer/core/camera.h"

#include "renderer/core/motion_steps.h"
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

Camera camera_at(const std::vector<Camera>& steps, float time) {
  const auto [k, f] = step_position(steps.size(), time);
  const Camera &a = steps[k], &b = steps[k + 1];
  Camera c = a;
  c.position = lerp_steps(a.position, b.position, f);
  c.forward = normalize(lerp_steps(a.forward, b.forward, f));
  c.right = normalize(cross(c.forward, lerp_steps(a.up, b.up, f)));
  c.up = cross(c.right, c.forward);
  c.tan_half_x = lerp_steps(a.tan_half_x, b.tan_half_x, f);
  c.tan_half_y = lerp_steps(a.tan_half_y, b.tan_half_y, f);
  c.lens_radius = lerp_steps(a.lens_radius, b.lens_radius, f);
  c.focus_distance = lerp_steps(a.focus_distance, b.focus_distance, f);
  return c;
}

}  // namespace vesper
