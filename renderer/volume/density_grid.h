#pragma once
// A scalar voxel grid (density, temperature...) sampled trilinearly in index
// space. Backed by a NanoVDB grid converted from OpenVDB at load time; this
// header does not expose NanoVDB or OpenVDB.
#include <array>
#include <memory>
#include <string>

#include "renderer/math/transform.h"
#include "renderer/math/vec.h"

namespace vesper {

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
  virtual const Transform& index_to_world() const = 0;
  virtual float max_value() const = 0;
  virtual const std::string& name() const = 0;
};

}  // namespace vesper
