#pragma once
#include "renderer/media/media_set.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

struct MediaBuildOptions {
  bool majorant_grid = true;  // false: one global majorant per grid (baseline for benchmarks)
  int majorant_cell_voxels = 16;
};

// Converts the described media to render space (coefficients per render unit).
MediaSet build_media(const SceneDescription& desc, const Vec3d& origin, double unit_scale,
                     const MediaBuildOptions& options);

}  // namespace vesper
