#pragma once
// Subcommand entry points. Each lives in its own .cpp; main.cpp owns CLI11
// and only fills these option structs.
#include <optional>
#include <string>
#include <vector>

namespace vesper::cli {

struct RenderCommandOptions {
  std::string scene;
  std::string output;
  std::optional<int> spp;
  std::optional<int> threads;
  std::optional<unsigned long long> seed;
  std::optional<std::string> aovs;  // comma-separated
  int sample_begin = 0;
  std::optional<int> sample_end;
  bool quiet = false;
};
int run_render(const RenderCommandOptions& options);

// vesper vdb cloud: a procedural cloud written as an OpenVDB fog volume.
struct VdbCloudOptions {
  std::string output;
  int resolution = 128;
  unsigned long long seed = 1;
  std::optional<double> voxel_size;  // default: 2.56 / resolution (same world size)
  std::optional<float> noise_amplitude;
  std::optional<int> noise_octaves;
  std::string grid = "density";
  bool quiet = false;
};
int run_vdb_cloud(const VdbCloudOptions& options);

// vesper vdb info: the grids of a .vdb file (type, active voxels, bbox, range).
struct VdbInfoOptions {
  std::string file;
};
int run_vdb_info(const VdbInfoOptions& options);

}  // namespace vesper::cli
