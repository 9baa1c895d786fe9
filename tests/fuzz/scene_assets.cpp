// scene_assets.h: real files for the scene target, so that accepted scenes
// reach the mesh, image and VDB loaders.
#include "tests/fuzz/scene_assets.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "renderer/volume/vdb_io.h"
#include "tests/fuzz/fuzz_target.h"

namespace vesper::fuzz {
namespace {

void write_sky(const std::filesystem::path& file) {
  const int w = 8, h = 4;
  std::vector<float> px(size_t(w * h * 3));
  for (size_t i = 0; i < px.size(); ++i) px[i] = 0.1f + 0.05f * float(i % 7);
  auto out = OIIO::ImageOutput::create(file.string());
  const OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
  if (!out || !out->open(file.string(), spec) ||
      !out->write_image(OIIO::TypeDesc::FLOAT, px.data()) || !out->close())
    finding("cannot write the fuzz sandbox's " + file.string());
}

void write_cloud(const std::filesystem::path& file) {
  DenseVolume v;
  v.nx = v.ny = v.nz = 8;
  v.voxel_size = 0.25;
  v.origin = Vec3d(-1.0);
  v.values.resize(8 * 8 * 8);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const double r = std::hypot(i - 3.5, j - 3.5, k - 3.5) / 4.0;
        v.values[size_t((k * 8 + j) * 8 + i)] = float(std::max(0.0, 1.0 - r));
      }
  write_vdb_fog_volume(v, "density", file);
}

struct SceneFiles {
  std::filesystem::path dir;
  SceneFiles() : dir(sandbox()) {
    const std::filesystem::path src(VESPER_SOURCE_DIR);
    const auto copy = std::filesystem::copy_options::overwrite_existing;
    std::filesystem::copy_file(src / "scenes/cornell/cube.obj", dir / "cube.obj", copy);
    std::filesystem::copy_file(src / "tests/renderer/data/meshes/quad.obj", dir / "quad.obj", copy);
    std::filesystem::copy_file(src / "tests/renderer/data/meshes/pyramid.ply", dir / "pyramid.ply",
                               copy);
    write_sky(dir / "sky.exr");
    write_cloud(dir / "cloud.vdb");
  }
};

}  // namespace

const std::filesystem::path& scene_sandbox() {
  static const SceneFiles files;
  return files.dir;
}

}  // namespace vesper::fuzz
