// The server's expected scene hash of a scene over time is, per frame, the
// hash the renderer's loader computes for that frame (docs/scene-format.md,
// "Scene hash"): one definition on both sides, so farm frames are accepted.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "common/sha256.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/volume/vdb_io.h"
#include "server/blob_store.h"
#include "server/result_check.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

TEST(FrameExpectations, EachFrameHashesAsTheLoaderHashesIt) {
  test::TempDir dir("server");
  BlobStore blobs(dir / "blobs");
  const fs::path task = dir / "task";
  fs::create_directories(task / "assets/seq");
  Lease lease;
  lease.task.job_id = 1;
  // Three frames of a sequence, the second and third with the same bytes.
  for (int f = 1; f <= 3; ++f) {
    DenseVolume v;
    v.nx = v.ny = v.nz = 2;
    v.values.assign(8, f == 1 ? 1.0f : 2.0f);
    const fs::path file = task / ("assets/seq/s." + std::to_string(f) + ".vdb");
    if (f == 3)
      fs::copy_file(task / "assets/seq/s.2.vdb", file);
    else
      write_vdb_fog_volume(v, "density", file);
    std::ifstream in(file, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), {}};
    blobs.put(sha256_hex(bytes), bytes);
    lease.assets.push_back({"assets/seq/s." + std::to_string(f) + ".vdb", sha256_hex(bytes)});
  }
  const json scene = json::parse(R"({"format": "vesper-scene/1",
    "camera": {"type": "perspective", "from": [0, 0, 4], "to": [0, 0, 0], "up": [0, 1, 0],
               "fov": {"keys": [[1, 30], [2, 40]]}},
    "film": {"width": 4, "height": 4}, "render": {"spp": 1, "seed": 3},
    "materials": {}, "shapes": [],
    "media": {"smoke": {"type": "vdb", "file": "assets/seq/s.#.vdb"}}})");
  const std::string text = scene.dump();
  lease.scene = sha256_hex(text);
  blobs.put(lease.scene, text);
  std::ofstream(task / "scene.json") << text;

  ResultExpectations expectations(blobs);
  std::vector<std::string> hashes;
  for (int f = 1; f <= 3; ++f) {
    lease.task.frame = f;
    const ExpectedResult e = expectations.of(lease);
    const SceneDescription loaded =
        load_scene(task / "scene.json", {.scene_dir_only = true, .frame = double(f)});
    EXPECT_EQ(e.scene_hash, loaded.content_hash) << "frame " << f;
    hashes.push_back(e.scene_hash);
    // Asked again (now from the cache): the same frame's hash.
    EXPECT_EQ(expectations.of(lease).scene_hash, e.scene_hash);
  }
  EXPECT_NE(hashes[0], hashes[1]);  // fov and file differ
  EXPECT_EQ(hashes[1], hashes[2]);  // fov held, same bytes
}

}  // namespace
}  // namespace vesper
