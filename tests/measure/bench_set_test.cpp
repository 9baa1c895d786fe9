// vesper-bench/1 files: the project's own set loads; each mistake is named
// by file and JSON path (docs/bench.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "measure/bench_set.h"
#include "tests/common/temp_dir.h"

namespace vesper::measure {
namespace {

namespace fs = std::filesystem;

class BenchSetTest : public ::testing::Test {
 protected:
  BenchSetTest() {
    fs::create_directories(dir_ / "s");
    std::ofstream(dir_ / "s/scene.json") << "{}";  // the set does not read scenes
  }
  // A set with one scene whose keys are `scene`, and top-level extras `top`.
  BenchSet parse(const std::string& scene, const std::string& top = "") {
    const std::string text =
        R"({"format": "vesper-bench/1", )" + top + R"("scenes": [{)" + scene + "}]}";
    return parse_bench_set_text(text, dir_ / "set.json");
  }
  // The message of the BenchSetError `scene` raises (file and path checked).
  std::string error(const std::string& scene, const std::string& path,
                    const std::string& top = "") {
    try {
      parse(scene, top);
    } catch (const BenchSetError& e) {
      EXPECT_EQ(e.file(), (dir_ / "set.json").string());
      EXPECT_EQ(e.json_path(), path) << e.what();
      return e.message();
    }
    ADD_FAILURE() << "no error for " << scene;
    return "";
  }
  test::TempDir temp_{"measure"};
  fs::path dir_ = temp_.path();
  const std::string ok_ = R"("name": "a", "path": "s/scene.json", "kind": "surface", )"
                          R"("width": 64, "height": 48, "spp": [1, 2, 4], "reference_spp": 256)";
};

TEST_F(BenchSetTest, TheProjectsSetLoadsWithQuickSettings) {
  const BenchSet set = load_bench_set(fs::path(VESPER_SOURCE_DIR) / "bench/scenes.json");
  ASSERT_GE(set.scenes.size(), 6u);
  for (const auto& s : set.scenes) {
    EXPECT_TRUE(fs::is_regular_file(s.path)) << s.path;
    EXPECT_EQ(s.quick.spp_ladder, (std::vector<int>{1, 4, 16}));
    EXPECT_EQ(s.quick.reference_spp, 64);
  }
}

TEST_F(BenchSetTest, ResolvesPathsAndMergesQuickOverrides) {
  const BenchSet set = parse(ok_ + R"(, "quick": {"spp": [1, 3]})",
                             R"("quick": {"width": 8, "height": 6, "reference_spp": 4}, )");
  const BenchSetScene& s = set.scenes.at(0);
  EXPECT_EQ(s.path, (dir_ / "s/scene.json").lexically_normal());
  EXPECT_EQ(s.full.width, 64);
  EXPECT_EQ(s.full.spp_ladder, (std::vector<int>{1, 2, 4}));
  EXPECT_EQ(s.quick.width, 8);
  EXPECT_EQ(s.quick.spp_ladder, (std::vector<int>{1, 3}));
  EXPECT_EQ(s.quick.reference_spp, 4);
}

TEST_F(BenchSetTest, MistakesNameTheirJsonPath) {
  EXPECT_NE(error(R"("name": "a", "path": "s/scene.json", "kind": "surface", "width": 64, )"
                  R"("height": 48, "spp": [1, 4, 2], "reference_spp": 256)",
                  "/scenes/0/spp/2")
                .find("increases"),
            std::string::npos);
  EXPECT_NE(error(R"("name": "a", "path": "s/scene.json", "kind": "surface", "width": 64, )"
                  R"("height": 48, "spp": [1], "reference_spp": 255)",
                  "/scenes/0/reference_spp")
                .find("even"),
            std::string::npos);
  EXPECT_NE(error(R"("name": "a", "path": "nope.json", "kind": "surface", "width": 64, )"
                  R"("height": 48, "spp": [1], "reference_spp": 2)",
                  "/scenes/0/path")
                .find("no scene file"),
            std::string::npos);
  EXPECT_NE(error(R"("name": "a", "path": "s/scene.json", "kind": "solid", "width": 64, )"
                  R"("height": 48, "spp": [1], "reference_spp": 2)",
                  "/scenes/0/kind")
                .find("surface"),
            std::string::npos);
  error(ok_ + R"(, "witdh": 3)", "/scenes/0/witdh");
  error(ok_ + R"(, "quick": {"spp": []})", "/scenes/0/quick/spp");
  error(ok_, "/quick/width", R"("quick": {"width": 0}, )");
}

TEST_F(BenchSetTest, FormatAndDuplicateNamesAreChecked) {
  EXPECT_THROW(
      parse_bench_set_text(R"({"format": "vesper-bench/2", "scenes": []})", dir_ / "set.json"),
      BenchSetError);
  const std::string two =
      R"({"format": "vesper-bench/1", "scenes": [{)" + ok_ + "}, {" + ok_ + "}]}";
  try {
    parse_bench_set_text(two, dir_ / "set.json");
    ADD_FAILURE() << "duplicate name accepted";
  } catch (const BenchSetError& e) {
    EXPECT_EQ(e.json_path(), "/scenes/1/name");
    EXPECT_NE(e.message().find("already at /scenes/0"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_bench_set(dir_ / "missing.json"), BenchSetError);
}

}  // namespace
}  // namespace vesper::measure
