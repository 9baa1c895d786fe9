#pragma once
// A scalar voxel grid (density, temperature...) sampled trilinearly in index
// space. Backed by a NanoVDB grid converted from OpenVDB at load time; this
// header does not expose NanoVDB or OpenVDB.
#include <array>
#include <memory>
#include <string>

#include "renderer/math/vec.h"

namespace vesper {

// Row-major 3x4 affine map (last row implicit 0 0 0 1).
struct Affine3d {
  std::array<double, 12> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  Vec3d apply_point(const Vec3d& p) const {
    return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
            m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
            m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
  }
  Vec3d apply_vector(const Vec3d& v) const {
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
            m[8] * v.x + m[9] * v.y + m[10] * v.z};
  }
};

struct IndexBox {
  std::array<int, 3> min{0, 0, 0},
      max{-1, -1, -1};  // inclusive voxel coordinates; empty if max < min
  bool empty() const { return max[0] < min[0] || max[1] < min[1] || max[2] < min[2]; }
};

class DensityGrid {
 public:
  virtual ~DensityGrid() = default;
  // Trilinear interpolation at a continuous index-space position; voxel (i,j,k)
  // has its value at (i,j,k); 0 outside the active voxels (background).
  virtual float sample(const Vec3& index_pos) const = 0;
  // Value of one voxel.
  virtual float voxel(int i, int j, int k) const = 0;
  // Bounding box of the active voxels.
  virtual IndexBox active_box() const = 0;
  // The grid's own index -> world transform (from the .vdb file).
  virtual const Affine3d& index_to_world() const = 0;
  virtual float max_value() const = 0;
  virtual const std::string& name() const = 0;
};

}  // namespace vesper
