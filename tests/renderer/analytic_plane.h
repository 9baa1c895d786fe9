#pragma once
// A diffuse plane y = 0 seen from above, checked against closed-form
// irradiance: shared by the analytic light tests and the light-selection
// tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "render_stats.h"
#include "renderer/scene/scene.h"

namespace vesper::test {

// Irradiance at p with normal n from a Lambertian polygon of radiance L:
// E = L/2 * sum_i acos(v_i . v_i+1) * (n . normalize(v_i x v_i+1)), v_i unit
// vectors toward the vertices in order (Lambert 1760; Arvo 1995).
inline double polygon_irradiance(const Vec3d& p, const Vec3d& n, const std::array<Vec3d, 4>& verts,
                                 double L) {
  double sum = 0;
  for (int i = 0; i < 4; ++i) {
    const Vec3d a = normalize(verts[size_t(i)] - p), b = normalize(verts[size_t((i + 1) % 4)] - p);
    const double angle = std::acos(std::clamp(dot(a, b), -1.0, 1.0));
    sum += angle * dot(n, normalize(cross(a, b)));
  }
  return 0.5 * L * std::abs(sum);
}

// Each 4x4 tile's mean luminance over `batches` renders of `spp` must match
// rho/pi * E(x) averaged over its pixels (8x8 quadrature per pixel through
// the camera onto y = 0): a Sidak-corrected t-test at family-wise alpha = 0.01.
template <typename Irradiance>
void expect_plane_tiles_match(const Scene& scene, double rho, const Irradiance& irradiance,
                              int batches, int spp) {
  auto expected_pixel = [&](int x, int y) {
    double sum = 0;
    for (int sy = 0; sy < 8; ++sy)
      for (int sx = 0; sx < 8; ++sx) {
        const Ray r =
            scene.camera.generate_ray(x + (sx + 0.5f) / 8.f, y + (sy + 0.5f) / 8.f, {0.5f, 0.5f});
        const Vec3d o = Vec3d(r.origin) * scene.unit_scale + scene.origin, dir(r.dir);
        sum += rho / M_PI * irradiance(o + dir * (-o.y / dir.y));
      }
    return sum / 64.0;
  };
  const int tile = 4;
  const TileStats st = tile_stats(scene, batches, spp, tile);
  const double crit = sidak_t_critical(0.01, int(st.mean.size()), st.batches - 1);
  for (int ty = 0; ty < st.tiles_y; ++ty)
    for (int tx = 0; tx < st.tiles_x; ++tx) {
      double expect = 0;
      for (int y = ty * tile; y < (ty + 1) * tile; ++y)
        for (int x = tx * tile; x < (tx + 1) * tile; ++x) expect += expected_pixel(x, y);
      expect /= tile * tile;
      const size_t t = size_t(ty * st.tiles_x + tx);
      const double se = std::max(st.se[t], 1e-6 * expect + 1e-12);  // delta lights: no noise at all
      EXPECT_LT(std::abs(st.mean[t] - expect) / se, crit)
          << "tile " << tx << "," << ty << " rendered " << st.mean[t] << " analytic " << expect;
    }
}

}  // namespace vesper::test
