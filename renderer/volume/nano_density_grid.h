#pragma once
// The concrete DensityGrid: a NanoVDB float grid (converted from OpenVDB by
// vdb_io.cpp). Includes NanoVDB (header only, light) but never OpenVDB.
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/HostBuffer.h>

#include <string>

#include "renderer/volume/density_grid.h"

namespace vesper {

class NanoDensityGrid final : public DensityGrid {
 public:
  // handle must hold a nanovdb::FloatGrid whose inactive values are 0.
  NanoDensityGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
                  const Transform& index_to_world, const IndexBox& active_box, float max_value);

  // Thread-safe: each call uses its own ReadAccessor (construction is a few
  // pointer copies; the accessor's node cache then serves the 8 corner reads).
  float sample(const Vec3& index_pos) const override;
  float voxel(int i, int j, int k) const override;
  IndexBox active_box() const override { return box_; }
  const Transform& index_to_world() const override { return xform_; }
  float max_value() const override { return max_; }
  const std::string& name() const override { return name_; }

  const nanovdb::FloatGrid& nano_grid() const { return *grid_; }
  size_t memory_bytes() const { return handle_.size(); }

 private:
  nanovdb::GridHandle<nanovdb::HostBuffer> handle_;
  const nanovdb::FloatGrid* grid_ = nullptr;
  std::string name_;
  Transform xform_;
  IndexBox box_;
  float max_ = 0;
};

}  // namespace vesper
