#include "renderer/volume/nano_density_grid.h"

#include <cmath>
#include <stdexcept>

namespace vesper {

NanoDensityGrid::NanoDensityGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
                                 const Transform& index_to_world, const IndexBox& active_box,
                                 float max_value)
    : handle_(std::move(handle)),
      name_(std::move(name)),
      xform_(index_to_world),
      box_(active_box),
      max_(max_value) {
  grid_ = handle_.grid<float>();
  if (!grid_) throw std::invalid_argument("NanoDensityGrid: the handle does not hold a float grid");
}

float NanoDensityGrid::sample(const Vec3& p) const {
  // Hand-written trilinear over the 8 voxels around p (voxel centres at integer
  // coordinates). Outside the tree's bounds the reads return the background (0).
  const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  // Far outside int range (or NaN): nothing there.
  if (!(std::abs(fx) < 2.0e9f && std::abs(fy) < 2.0e9f && std::abs(fz) < 2.0e9f)) return 0.0f;
  const float u = p.x - fx, v = p.y - fy, w = p.z - fz;
  nanovdb::Coord c{int(fx), int(fy), int(fz)};
  auto acc = grid_->getAccessor();
  const float v000 = acc.getValue(c);
  c[2] += 1;
  const float v001 = acc.getValue(c);
  c[1] += 1;
  const float v011 = acc.getValue(c);
  c[2] -= 1;
  const float v010 = acc.getValue(c);
  c[0] += 1;
  const float v110 = acc.getValue(c);
  c[2] += 1;
  const float v111 = acc.getValue(c);
  c[1] -= 1;
  const float v101 = acc.getValue(c);
  c[2] -= 1;
  const float v100 = acc.getValue(c);
  const float a00 = v000 + (v001 - v000) * w, a01 = v010 + (v011 - v010) * w;
  const float a10 = v100 + (v101 - v100) * w, a11 = v110 + (v111 - v110) * w;
  const float b0 = a00 + (a01 - a00) * v, b1 = a10 + (a11 - a10) * v;
  return b0 + (b1 - b0) * u;
}

float NanoDensityGrid::voxel(int i, int j, int k) const {
  return grid_->tree().getValue(nanovdb::Coord(i, j, k));
}

}  // namespace vesper
