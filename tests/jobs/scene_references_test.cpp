// The files a scene document references, with their JSON paths.
#include "jobs/scene_references.h"

#include <gtest/gtest.h>

namespace vesper {
namespace {

TEST(SceneReferences, EveryFileKeyWithItsJsonPath) {
  const auto scene = nlohmann::json::parse(R"({
    "shapes": [{"type": "sphere"}, {"type": "mesh", "file": "cube.obj"}],
    "lights": [{"type": "environment", "file": "/home/u/sky.exr"}],
    "media": {"smo/ke": {"type": "vdb", "file": "../smoke.vdb"}},
    "layers": {"file": {"paths": "all"}}})");
  const auto refs = scene_file_references(scene);
  ASSERT_EQ(refs.size(), 3u);
  EXPECT_EQ(refs[0].json_path, "/lights/0/file");
  EXPECT_EQ(refs[0].file, "/home/u/sky.exr");
  EXPECT_EQ(refs[1].json_path, "/media/smo~1ke/file");
  EXPECT_EQ(refs[2].json_path, "/shapes/1/file");
  EXPECT_EQ(outside_reference(scene).value_or(""),
            "/lights/0/file: '/home/u/sky.exr' is an absolute path (a farm task's files must be "
            "inside its scene directory)");
  EXPECT_FALSE(outside_reference(nlohmann::json::parse(R"({"a": {"file": "in/side.obj"}})")));
}

}  // namespace
}  // namespace vesper
