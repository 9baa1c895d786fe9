// The worker's blob cache cap: least recently used blobs go first, never one
// the current task uses, and task directories linking an evicted blob go too.
#include "worker/cache_eviction.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "common/sha256.h"
#include "tests/common/temp_dir.h"
#include "worker/task_dir.h"

namespace fs = std::filesystem;

namespace vesper::worker_detail {
namespace {

class CacheEvictionTest : public ::testing::Test {
 protected:
  // A cached asset of `size` bytes last used `age` seconds ago.
  std::string put(char fill, size_t size, int age) {
    const std::string bytes(size, fill);
    const std::string h = sha256_hex(bytes);
    const fs::path f = asset_cache_file(cache_, h);
    std::ofstream(f, std::ios::binary) << bytes;
    fs::last_write_time(f, fs::file_time_type::clock::now() - std::chrono::seconds(age));
    return h;
  }
  bool cached(const std::string& h) const { return fs::exists(asset_cache_file(cache_, h)); }

  test::TempDir temp_{"cache"};
  fs::path cache_ = temp_.path();
};

TEST_F(CacheEvictionTest, EvictsLeastRecentlyUsedUntilUnderTheCap) {
  const std::string oldest = put('a', 1000, 300), old = put('b', 1000, 200),
                    recent = put('c', 1000, 100), newest = put('d', 1000, 0);
  const Evicted e = evict_lru(cache_, 2500, {});
  EXPECT_EQ(e.blobs, 2);
  EXPECT_EQ(e.bytes, 2000u);
  EXPECT_FALSE(cached(oldest));
  EXPECT_FALSE(cached(old));
  EXPECT_TRUE(cached(recent));
  EXPECT_TRUE(cached(newest));
  // Under the cap: nothing more goes.
  EXPECT_EQ(evict_lru(cache_, 2500, {}).blobs, 0);
}

TEST_F(CacheEvictionTest, NeverEvictsTheCurrentTasksBlobs) {
  const std::string in_use = put('a', 1000, 300), other = put('b', 1000, 200),
                    newest = put('c', 1000, 0);
  const Evicted e = evict_lru(cache_, 1000, {in_use});
  EXPECT_EQ(e.blobs, 2);
  EXPECT_TRUE(cached(in_use));  // over the cap still, but the task needs it
  EXPECT_FALSE(cached(other));
  EXPECT_FALSE(cached(newest));
}

TEST_F(CacheEvictionTest, MarkUsedMakesABlobTheMostRecent) {
  const std::string a = put('a', 1000, 300), b = put('b', 1000, 200);
  mark_used(asset_cache_file(cache_, a));
  evict_lru(cache_, 1000, {});
  EXPECT_TRUE(cached(a));
  EXPECT_FALSE(cached(b));
}

TEST_F(CacheEvictionTest, TaskDirectoriesLinkingAnEvictedBlobGoToo) {
  fs::create_directories(cache_ / "tmp");
  const std::string scene_bytes = "{\"format\": \"vesper-scene/1\"}";
  const std::string scene = sha256_hex(scene_bytes);
  std::ofstream(cache_ / (scene + ".json"), std::ios::binary) << scene_bytes;
  fs::last_write_time(cache_ / (scene + ".json"),
                      fs::file_time_type::clock::now() - std::chrono::seconds(500));
  const std::string mesh = put('m', 4000, 400), keep = put('k', 100, 0);
  const fs::path dir = materialise_task_dir(cache_, scene, {{"mesh.obj", mesh}}, "t1");
  ASSERT_TRUE(fs::exists(dir / "mesh.obj"));
  const Evicted e = evict_lru(cache_, 1000, {keep});
  EXPECT_EQ(e.blobs, 2);  // the scene and the mesh, oldest first
  EXPECT_FALSE(fs::exists(dir)) << "its hard links would keep the bytes on disk";
  EXPECT_TRUE(cached(keep));
}

}  // namespace
}  // namespace vesper::worker_detail
