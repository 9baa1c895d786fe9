#pragma once
// Procedural DensityGrid implementations for tests: exact, file-free stand-ins
// for OpenVDB grids (the VDB path itself is tested in vdb_test.cpp).
#include <cmath>
#include <functional>
#include <string>

#include "renderer/volume/density_grid.h"

namespace vesper::test {

// Trilinear interpolation of f at the voxels, on the continuous index box
// [0, n-1]^3, 0 outside; voxel size
// `voxel` and world offset `origin` in index_to_world.
class FunctionGrid : public DensityGrid {
 public:
  FunctionGrid(int n, double voxel, Vec3d origin, std::function<float(const Vec3&)> f,
               std::string name = "density")
      : n_(n),
        f_(std::move(f)),
        name_(std::move(name)),
        xf_(Transform::translate(origin) * Transform::scale(Vec3d(voxel))) {
    max_ = 0.f;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) max_ = std::max(max_, voxel_value(i, j, k));
  }
  float sample(const Vec3& p) const override {
    const float hi = float(n_ - 1);
    if (p.x < 0.f || p.y < 0.f || p.z < 0.f || p.x > hi || p.y > hi || p.z > hi) return 0.f;
    // Trilinear between voxel values, like the NanoVDB sampler.
    const int i = std::min(int(p.x), n_ - 2), j = std::min(int(p.y), n_ - 2),
              k = std::min(int(p.z), n_ - 2);
    const float fx = p.x - float(i), fy = p.y - float(j), fz = p.z - float(k);
    float v = 0.f;
    for (int c = 0; c < 8; ++c) {
      const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
      v += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz) *
           voxel_value(i + dx, j + dy, k + dz);
    }
    return v;
  }
  float voxel(int i, int j, int k) const override { return voxel_value(i, j, k); }
  IndexBox active_box() const override { return {{0, 0, 0}, {n_ - 1, n_ - 1, n_ - 1}}; }
  const Transform& index_to_world() const override { return xf_; }
  float max_value() const override { return max_; }
  const std::string& name() const override { return name_; }

 private:
  float voxel_value(int i, int j, int k) const { return f_(Vec3(float(i), float(j), float(k))); }
  int n_;
  std::function<float(const Vec3&)> f_;
  std::string name_;
  Transform xf_;
  float max_ = 0;
};

}  // namespace vesper::test
