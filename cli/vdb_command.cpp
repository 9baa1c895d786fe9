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
#include "common/frame_pattern.h"
#include "jobs/frame_range.h"
#include "renderer/volume/cloud.h"
#include "renderer/volume/vdb_io.h"

namespace vesper::cli {

namespace {

// The frames to write and where: one file without --frames, else a file a frame.
std::vector<std::pair<int, std::filesystem::path>> cloud_files(const VdbCloudOptions& o) {
  if (!o.frames) return {{1, o.output}};
  const std::vector<int> frames = parse_frame_range(*o.frames);  // FrameRangeError
  if (frames.size() > 1 && !has_frame_pattern(o.output))
    throw std::invalid_argument(o.output + ": " + std::to_string(frames.size()) +
                                " frames need a frame pattern ('#') in the output name, e.g. "
                                "cloud.####.vdb");
  std::vector<std::pair<int, std::filesystem::path>> out;
  for (const int f : frames) out.emplace_back(f, frame_path(o.output, f));
  return out;
}

}  // namespace

int run_vdb_cloud(const VdbCloudOptions& o) {
  CloudParams p;
  p.resolution = o.resolution;
  p.seed = o.seed;
  // Keep the cloud the same world size at any resolution (2.56 units wide).
  p.voxel_size = o.voxel_size.value_or(2.56 / double(o.resolution > 0 ? o.resolution : 1));
  if (o.noise_amplitude) p.noise_amplitude = *o.noise_amplitude;
  if (o.noise_octaves) p.noise_octaves = *o.noise_octaves;
  try {
    for (const auto& [frame, file] : cloud_files(o)) {
      const auto t0 = std::chrono::steady_clock::now();
      p.time = double(frame) - 1;
      const DenseVolume v = generate_cloud(p);
      write_vdb_fog_volume(v, o.grid, file);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!o.quiet)
        spdlog::info(
            "cloud{}: {}x{}x{} voxels of {:g} units, seed {}, grid '{}' written in {:.2f} s",
            o.frames ? fmt::format(" frame {}", frame) : "", v.nx, v.ny, v.nz, v.voxel_size, p.seed,
            o.grid, s);
      std::printf("%s\n", file.c_str());
      std::fflush(stdout);
    }
  } catch (const FrameRangeError& e) {
    spdlog::error("--frames: {}", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const VdbError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
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
