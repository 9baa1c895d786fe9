#pragma once
// OpenVDB file input/output. All OpenVDB code lives in vdb_io.cpp (its header
// costs seconds of compile per translation unit).
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/volume/density_grid.h"

namespace vesper {

// what() names the file and the problem; for a missing or wrong-typed grid it
// lists the grids the file has, with their types.
class VdbError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Loads one float grid by name and converts it to NanoVDB for sampling.
// Rejects: unreadable file, missing grid, non-float grid, NaN/Inf voxels,
// negative values (when reject_negative), an empty grid.
std::shared_ptr<const DensityGrid> load_vdb_grid(const std::filesystem::path& file,
                                                 const std::string& grid_name,
                                                 bool reject_negative = true);

// Names and value types of every grid in a file ("density: float").
std::vector<std::string> list_vdb_grids(const std::filesystem::path& file);

// Everything `vesper vdb info` shows about one grid. Value range and active
// counts are read from the grid itself (the file's metadata can be absent).
struct VdbGridInfo {
  std::string name;
  std::string value_type;  // "float", "vec3s", ...
  std::string grid_class;  // "fog volume", "level set", "unknown", ...
  unsigned long long active_voxels = 0;
  IndexBox active_box;
  bool has_range = false;  // scalar (float/double/int) grids only
  double min_value = 0, max_value = 0;
  double background = 0;     // scalar grids only
  Transform index_to_world;  // identity when the transform is not linear
  bool linear_transform = true;
};
std::vector<VdbGridInfo> describe_vdb_grids(const std::filesystem::path& file);

// A dense block of voxels to write as an OpenVDB fog volume (values < cutoff
// are left inactive). index_to_world is a uniform voxel size + translation.
struct DenseVolume {
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> values;  // x fastest: (k * ny + j) * nx + i
  double voxel_size = 1;
  Vec3d origin;  // world position of voxel (0,0,0)
};
void write_vdb_fog_volume(const DenseVolume& volume, const std::string& grid_name,
                          const std::filesystem::path& file, float cutoff = 1e-6f);

}  // namespace vesper
