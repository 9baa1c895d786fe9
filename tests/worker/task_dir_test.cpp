// The worker's task directory: scene.json and assets hard-linked from the
// cache, names re-checked, a complete directory reused, a corrupt one rebuilt.
#include "worker/task_dir.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/sha256.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;

namespace vesper::worker_detail {
namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class TaskDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(cache_ / "tmp");
    scene_ = put("{\"format\": \"vesper-scene/1\"}", true);
    mesh_ = put("v 0 0 0\n", false);
  }
  std::string put(const std::string& bytes, bool scene) {
    const std::string h = sha256_hex(bytes);
    std::ofstream(scene ? cache_ / (h + ".json") : asset_cache_file(cache_, h), std::ios::binary)
        << bytes;
    return h;
  }
  test::TempDir temp_{"taskdir"};
  fs::path cache_ = temp_.path();
  std::string scene_, mesh_;
};

TEST_F(TaskDirTest, HoldsTheSceneAndTheAssetsAtTheirNames) {
  const std::vector<Asset> assets = {{"assets/deep/cube.obj", mesh_}, {"top.obj", mesh_}};
  const fs::path dir = materialise_task_dir(cache_, scene_, assets, "a");
  EXPECT_EQ(dir, cache_ / "jobs" / task_dir_key(scene_, assets));
  EXPECT_NE(task_dir_key(scene_, assets), scene_);
  EXPECT_EQ(task_dir_key(scene_, {}), scene_);
  EXPECT_TRUE(fs::equivalent(dir / "scene.json", cache_ / (scene_ + ".json")));
  EXPECT_TRUE(fs::equivalent(dir / "assets/deep/cube.obj", asset_cache_file(cache_, mesh_)));
  EXPECT_EQ(slurp(dir / "top.obj"), "v 0 0 0\n");
  // Reused as it is; no temp directory left behind.
  EXPECT_EQ(materialise_task_dir(cache_, scene_, assets, "b"), dir);
  EXPECT_TRUE(fs::is_empty(cache_ / "tmp"));
  // A corrupted file in it (not the cached inode any more) gets it rebuilt.
  fs::remove(dir / "top.obj");
  std::ofstream(dir / "top.obj") << "evil";
  EXPECT_EQ(materialise_task_dir(cache_, scene_, assets, "c"), dir);
  EXPECT_EQ(slurp(dir / "top.obj"), "v 0 0 0\n");
  EXPECT_TRUE(fs::is_empty(cache_ / "tmp"));
}

TEST_F(TaskDirTest, NamesThatCouldEscapeAreRefused) {
  for (const char* bad : {"../x", "/etc/passwd", "a/../../b", "a//b", "", "a\\b", "scene.json"}) {
    EXPECT_THROW(materialise_task_dir(cache_, scene_, {{bad, mesh_}}, "x"), std::runtime_error)
        << bad;
  }
  EXPECT_THROW(materialise_task_dir(cache_, scene_, {{"a.obj", "../../etc"}}, "x"),
               std::runtime_error);
  EXPECT_THROW(materialise_task_dir(cache_, "../x", {}, "x"), std::runtime_error);
  // A file and a directory of the same name clash.
  EXPECT_THROW(materialise_task_dir(cache_, scene_, {{"a", mesh_}, {"a/b", mesh_}}, "x"),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(cache_ / "jobs" / scene_));
  EXPECT_TRUE(fs::is_empty(cache_ / "tmp"));
  EXPECT_FALSE(fs::exists(cache_.parent_path() / "x"));
}

}  // namespace
}  // namespace vesper::worker_detail
