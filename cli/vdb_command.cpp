// `vesper vdb cloud` (procedural cloud -> OpenVDB fog volume) and
// `vesper vdb info` (what a .vdb file holds). OpenVDB itself stays in
// renderer/volume/vdb_io.cpp; this file only uses its small header.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "cli/commands.h"
#include "renderer/volume/cloud.h"
#include "renderer/volume/vdb_io.h"

namespace vesper::cli {

int run_vdb_cloud(const VdbCloudOptions& o) {
  CloudParams p;
  p.resolution = o.resolution;
  p.seed = o.seed;
  // Keep the cloud the same world size at any resolution (2.56 units wide).
  p.voxel_size = o.voxel_size.value_or(2.56 / double(o.resolution > 0 ? o.resolution : 1));
  if (o.noise_amplitude) p.noise_amplitude = *o.noise_amplitude;
  if (o.noise_octaves) p.noise_octaves = *o.noise_octaves;
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const DenseVolume v = generate_cloud(p);
    write_vdb_fog_volume(v, o.grid, o.output);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.quiet)
      spdlog::info("cloud: {}x{}x{} voxels of {:g} units, seed {}, grid '{}' written in {:.2f} s",
                   v.nx, v.ny, v.nz, v.voxel_size, p.seed, o.grid, s);
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const VdbError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  std::printf("%s\n", o.output.c_str());
  return 0;
}

int run_vdb_info(const VdbInfoOptions& o) {
  std::vector<VdbGridInfo> grids;
  try {
    grids = describe_vdb_grids(o.file);
  } catch (const VdbError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  std::string out =
      fmt::format("{}: {} grid{}\n", o.file, grids.size(), grids.size() == 1 ? "" : "s");
  for (const VdbGridInfo& g : grids) {
    out += fmt::format("{} ({}, {})\n", g.name, g.value_type, g.grid_class);
    out += fmt::format("  active voxels: {}\n", g.active_voxels);
    if (g.active_box.empty())
      out += "  active bbox: empty\n";
    else
      out += fmt::format("  active bbox: [{}, {}, {}] -> [{}, {}, {}] ({} x {} x {})\n",
                         g.active_box.min[0], g.active_box.min[1], g.active_box.min[2],
                         g.active_box.max[0], g.active_box.max[1], g.active_box.max[2],
                         g.active_box.max[0] - g.active_box.min[0] + 1,
                         g.active_box.max[1] - g.active_box.min[1] + 1,
                         g.active_box.max[2] - g.active_box.min[2] + 1);
    if (g.has_range)
      out += fmt::format("  value range: [{:g}, {:g}], background {:g}\n", g.min_value, g.max_value,
                         g.background);
    if (g.linear_transform) {
      const auto& m = g.index_to_world.matrix().m;
      out += fmt::format(
          "  index to world: [{:g} {:g} {:g} {:g}; {:g} {:g} {:g} {:g}; {:g} {:g} {:g} {:g}]\n",
          m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9], m[10], m[11]);
    } else {
      out += "  index to world: non-linear (frustum) transform\n";
    }
  }
  std::fputs(out.c_str(), stdout);
  return 0;
}

}  // namespace vesper::cli
