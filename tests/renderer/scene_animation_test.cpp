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

namespace vesper {
namespace {

// A quad keyed to move during frame 2 only, rendered under a shutter.
nlohmann::json moving_quad_scene(const nlohmann::json& shutter) {
  nlohmann::json doc = test::minimal_scene();
  doc["render"]["shutter"] = shutter;
  doc["shapes"] = nlohmann::json::parse(R"([{"type": "quad", "material": "m",
      "corner": {"keys": [[1.5, [-1, -1, 0]], [2, [-0.5, -1, 0]]]},
      "edge1": [2, 0, 0], "edge2": [0, 2, 0]}])");
  return doc;
}

TEST(SceneAnimation, TheHashCoversTheMotionOverTheShutter) {
  const nlohmann::json blurred = moving_quad_scene({-0.5, 0});
  // Frames 2 and 3 hold the quad at the same place, but frame 2's shutter
  // [1.5, 2] sees it move: different scenes.
  EXPECT_NE(parse_scene(blurred, "s.json", {.frame = 2}).content_hash,
            parse_scene(blurred, "s.json", {.frame = 3}).content_hash);
  // Frames 3 and 4 are still over their shutters: the same scene.
  EXPECT_EQ(parse_scene(blurred, "s.json", {.frame = 3}).content_hash,
            parse_scene(blurred, "s.json", {.frame = 4}).content_hash);
  // Without a shutter frames 2 and 3 are one state.
  nlohmann::json sharp = blurred;
  sharp["render"].erase("shutter");
  EXPECT_EQ(parse_scene(sharp, "s.json", {.frame = 2}).content_hash,
            parse_scene(sharp, "s.json", {.frame = 3}).content_hash);
}

}  // namespace
}  // namespace vesper
