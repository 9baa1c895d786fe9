// A farm task's scene (`vesper render --scene-dir-only`) may only read files
// inside its directory: every kind of file reference is refused at its JSON
// path before anything is read; a local render keeps absolute paths.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "renderer/scene/scene_loader.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

json scene_with(const std::string& kind, const std::string& file) {
  json doc = json::parse(R"({
    "format": "vesper-scene/1",
    "camera": {"type": "perspective", "from": [0, 0, 4], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 30},
    "film": {"width": 16, "height": 8}, "render": {"spp": 1},
    "materials": {"m": {"type": "diffuse"}}, "shapes": []})");
  if (kind == "mesh")
    doc["shapes"] = json::array({{{"type", "mesh"}, {"file", file}, {"material", "m"}}});
  else if (kind == "environment")
    doc["lights"] = json::array({{{"type", "environment"}, {"file", file}}});
  else
    doc["media"] = {{"smoke", {{"type", "vdb"}, {"file", file}}}};
  return doc;
}

std::string error_of(const json& doc, const fs::path& file, bool scene_dir_only) {
  try {
    parse_scene(doc, file, SceneLoadOptions{scene_dir_only});
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneDirOnly, FilesOutsideTheSceneDirectoryAreRefusedAtTheirJsonPath) {
  const test::TempDir dir("scene-dir-only");
  const fs::path outside = dir / "outside.obj";
  std::ofstream(outside) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  fs::create_directories(dir / "task");
  const fs::path scene = dir / "task" / "scene.json";
  const std::pair<std::string, std::string> kinds[] = {
      {"mesh", "/shapes/0/file"}, {"environment", "/lights/0/file"}, {"vdb", "/media/smoke/file"}};
  for (const auto& [kind, path] : kinds)
    for (const std::string& ref :
         {outside.string(), std::string("../outside.obj"), std::string("sub/../../outside.obj")}) {
      const std::string err = error_of(scene_with(kind, ref), scene, true);
      EXPECT_NE(err.find(path + ": '" + ref + "' "), std::string::npos) << err;
      EXPECT_NE(err.find("inside its scene directory"), std::string::npos) << err;
    }
  // A local render of one's own scene reads the mesh by its absolute path.
  EXPECT_EQ(error_of(scene_with("mesh", outside.string()), scene, false), "(no error)");
  // Inside the directory is fine with the flag too.
  std::ofstream(dir / "task" / "inside.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(error_of(scene_with("mesh", "inside.obj"), scene, true), "(no error)");
}

}  // namespace
}  // namespace vesper
