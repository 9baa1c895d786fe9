#pragma once
// A coarse grid of maximum densities over blocks of voxels, walked along a ray
// with a 3D DDA, so that delta and ratio tracking take big steps through thin
// or empty space and never step in empty cells at all.
#include <functional>
#include <vector>

#include "renderer/volume/density_grid.h"

namespace vesper {

struct MajorantSegment {
  float t0 = 0, t1 = 0;   // ray parameter range
  float max_density = 0;  // upper bound of grid.sample() over the segment (grid units, not scaled)
};

class MajorantGrid {
 public:
  MajorantGrid() = default;
  // cell_voxels: voxels per cell side. The bound covers trilinear support
  // (each cell's max includes the one-voxel apron around it).
  MajorantGrid(const DensityGrid& grid, int cell_voxels = 16);
  // A single cell covering the whole grid (the "global majorant" baseline).
  static MajorantGrid global(const DensityGrid& grid);

  // Walks the ray o + t*d (index space; d need not be unit) over [tmin, tmax]
  // front to back, calling visit for each cell crossed; visit returns false to stop.
  void walk(const Vec3& o, const Vec3& d, float tmin, float tmax,
            const std::function<bool(const MajorantSegment&)>& visit) const;

  int cells_x() const { return res_[0]; }
  int cells_y() const { return res_[1]; }
  int cells_z() const { return res_[2]; }

 private:
  std::array<int, 3> res_{0, 0, 0};
  Vec3 lo_, cell_size_;  // index-space origin and size of a cell
  // Upper corner of the trilinear support (active.max + 1): the last cells
  // reach past it, and walk() must not hand out their majorant there.
  Vec3 hi_;
  std::vector<float> max_;
};

}  // namespace vesper
