// vesper submit's packing of a scene's files, sequences (`####`) included.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "cli/scene_package.h"
#include "tests/common/temp_dir.h"

namespace vesper::cli {
namespace {

namespace fs = std::filesystem;

fs::path write_sequence_scene(const test::TempDir& dir) {
  for (int f = 1; f <= 4; ++f) std::ofstream(dir / ("smoke.000" + std::to_string(f) + ".vdb")) << f;
  std::ofstream(dir / "cube.obj") << "v 0 0 0\n";
  std::ofstream(dir / "shot.json") << R"({"shapes": [{"type": "mesh", "file": "cube.obj"}],
      "media": {"smoke": {"type": "vdb", "file": "smoke.####.vdb"},
                "again": {"type": "vdb", "file": "./smoke.####.vdb"}}})";
  return dir / "shot.json";
}

TEST(ScenePackage, ASequencePacksTheJobsFramesUnderAFolderAndKeepsThePattern) {
  test::TempDir dir;
  const PackedScene p = pack_scene(write_sequence_scene(dir), {2, 3});
  const auto doc = nlohmann::json::parse(p.json);
  const std::string ref = doc["media"]["smoke"]["file"];
  EXPECT_TRUE(std::regex_match(ref, std::regex("assets/[0-9a-f]{12}/smoke\\.####\\.vdb"))) << ref;
  EXPECT_EQ(doc["media"]["again"]["file"], ref);  // one sequence, one folder
  const std::string folder = ref.substr(0, ref.rfind('/') + 1);
  std::vector<std::string> names;
  for (const PackedAsset& a : p.assets) names.push_back(a.name);
  ASSERT_EQ(names.size(), 3u);  // the mesh and frames 2 and 3
  EXPECT_NE(std::find(names.begin(), names.end(), folder + "smoke.0002.vdb"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), folder + "smoke.0003.vdb"), names.end());
  // Another take of the sequence (other bytes) is another folder.
  std::ofstream(dir / "smoke.0003.vdb") << "resimulated";
  const auto again = nlohmann::json::parse(pack_scene(dir / "shot.json", {2, 3}).json);
  EXPECT_NE(again["media"]["smoke"]["file"], ref);
}

TEST(ScenePackage, AMissingFrameIsNamedWithItsFileAndJsonPath) {
  test::TempDir dir;
  try {
    pack_scene(write_sequence_scene(dir), {4, 5});
    FAIL() << "frame 5 has no file";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/media/again/file"), std::string::npos) << what;
    EXPECT_NE(what.find("frame 5"), std::string::npos) << what;
    EXPECT_NE(what.find("smoke.0005.vdb"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace vesper::cli
