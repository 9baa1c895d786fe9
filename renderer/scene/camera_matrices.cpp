#include "renderer/scene/camera_matrices.h"

#include <cmath>

namespace vesper {

std::array<double, 2> camera_tan_half(const CameraDesc& camera, const FilmDesc& film) {
  const double t = std::tan(camera.fov_degrees * 0.5 * M_PI / 180.0);
  const double aspect = double(film.width) / double(film.height);
  return aspect >= 1 ? std::array<double, 2>{t * aspect, t} : std::array<double, 2>{t, t / aspect};
}

CameraMatrices camera_matrices(const CameraDesc& camera, const FilmDesc& film) {
  const Vec3d fwd = normalize(camera.to - camera.from);
  const Vec3d right = normalize(cross(fwd, camera.up));
  const Vec3d up = cross(right, fwd);
  const Vec3d back = -fwd;  // camera space +Z
  const Vec3d& o = camera.from;
  CameraMatrices m;
  // Columns are the camera axes: p * M = ((p - o)·right, (p - o)·up, (p - o)·back, 1).
  m.world_to_camera = {right.x,        up.x,        back.x,        0,  //
                       right.y,        up.y,        back.y,        0,  //
                       right.z,        up.z,        back.z,        0,  //
                       -dot(o, right), -dot(o, up), -dot(o, back), 1};
  // Then (x, y, z, 1) -> (x / tx, y / ty, 1, -z): divided by w = -z (the
  // distance in front), x and y span [-1, 1] over the image.
  const auto [tx, ty] = camera_tan_half(camera, film);
  const auto& c = m.world_to_camera;
  for (int r = 0; r < 4; ++r) {
    const double x = c[size_t(r * 4)], y = c[size_t(r * 4 + 1)], z = c[size_t(r * 4 + 2)],
                 w = c[size_t(r * 4 + 3)];
    m.world_to_ndc[size_t(r * 4)] = x / tx;
    m.world_to_ndc[size_t(r * 4 + 1)] = y / ty;
    m.world_to_ndc[size_t(r * 4 + 2)] = w;
    m.world_to_ndc[size_t(r * 4 + 3)] = -z;
  }
  return m;
}

}  // namespace vesper
