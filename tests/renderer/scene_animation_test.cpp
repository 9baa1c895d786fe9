// A scene over time: the loader parses the document of one frame, with every
// keyframed value evaluated at SceneLoadOptions::frame.
#include <gtest/gtest.h>

#include "renderer/scene/scene_loader.h"
#include "tests/renderer/minimal_scene.h"

namespace vesper {
namespace {

using nlohmann::json;

SceneDescription at_frame(const json& doc, double frame) {
  return parse_scene(doc, "shot.json", SceneLoadOptions{.frame = frame});
}

TEST(SceneAnimation, KeyframedValuesAreParsedAtTheFrame) {
  json doc = test::minimal_scene();
  doc["camera"]["fov"] = json::parse(R"({"keys": [[1, 20], [5, 60]]})");
  doc["camera"]["from"] = json::parse(R"({"keys": [[1, [0, 0, 4]], [3, [2, 0, 4]]]})");
  EXPECT_DOUBLE_EQ(at_frame(doc, 1).camera.fov_degrees, 20);
  EXPECT_DOUBLE_EQ(at_frame(doc, 2).camera.fov_degrees, 30);
  EXPECT_DOUBLE_EQ(at_frame(doc, 9).camera.fov_degrees, 60);
  EXPECT_DOUBLE_EQ(at_frame(doc, 2).camera.from.x, 1);
  EXPECT_DOUBLE_EQ(at_frame(doc, 2.5).camera.from.x, 1.5);
}

TEST(SceneAnimation, TheHashIsTheFramesEvaluatedState) {
  const json still = test::minimal_scene();
  EXPECT_EQ(at_frame(still, 1).content_hash, at_frame(still, 7).content_hash);

  json held = still;
  held["camera"]["fov"] = json::parse(R"({"keys": [[1, 30]]})");
  // A key that holds the scene's own value is the same state as the still scene.
  EXPECT_EQ(at_frame(held, 3).content_hash, at_frame(still, 3).content_hash);

  json moving = still;
  moving["camera"]["fov"] = json::parse(R"({"keys": [[1, 20], [5, 60]]})");
  EXPECT_NE(at_frame(moving, 2).content_hash, at_frame(moving, 3).content_hash);
  EXPECT_EQ(at_frame(moving, 5).content_hash, at_frame(moving, 8).content_hash);
}

TEST(SceneAnimation, AValueKeyedOutOfRangeIsRejectedAtTheFrameItReaches) {
  json doc = test::minimal_scene();
  doc["camera"]["fov"] = json::parse(R"({"keys": [[1, 30], [3, 190]]})");
  EXPECT_NO_THROW(at_frame(doc, 1));
  try {
    at_frame(doc, 3);
    FAIL() << "fov 190 at frame 3 was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "/camera/fov");
  }
}

}  // namespace
}  // namespace vesper
