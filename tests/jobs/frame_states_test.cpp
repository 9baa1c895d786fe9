// Per-frame states for result reuse (jobs/frame_states.h).
#include <gtest/gtest.h>

#include "jobs/frame_states.h"

namespace vesper {
namespace {

using nlohmann::json;

JobSpec spec_of(std::vector<int> frames, std::vector<Asset> assets) {
  JobSpec s;
  s.frames = std::move(frames);
  s.assets = std::move(assets);
  return s;
}

TEST(FrameStates, AStillSceneHasOneStateForEveryFrame) {
  const json scene =
      json::parse(R"({"camera": {"fov": 30}, "shapes": [{"file": "assets/a.obj"}]})");
  const auto states = frame_states(scene, spec_of({1, 2, 9}, {{"assets/a.obj", "b1"}}));
  ASSERT_EQ(states.size(), 3u);
  EXPECT_EQ(states.at(1), states.at(9));
  // The asset's blob is part of the state.
  EXPECT_NE(frame_states(scene, spec_of({1}, {{"assets/a.obj", "b2"}})).at(1), states.at(1));
}

TEST(FrameStates, AnEditOfKeysChangesOnlyTheFramesItChanges) {
  const json before =
      json::parse(R"({"camera": {"fov": {"keys": [[1, 30], [10, 30], [20, 50]]}}})");
  json after = before;
  after["camera"]["fov"]["keys"][2][1] = 60;
  std::vector<int> frames;
  for (int f = 1; f <= 24; ++f) frames.push_back(f);
  const auto a = frame_states(before, spec_of(frames, {}));
  const auto b = frame_states(after, spec_of(frames, {}));
  for (int f = 1; f <= 24; ++f) {
    if (f <= 10)
      EXPECT_EQ(a.at(f), b.at(f)) << f;
    else
      EXPECT_NE(a.at(f), b.at(f)) << f;
  }
  EXPECT_EQ(a.at(1), a.at(10));  // the same evaluated document
  EXPECT_NE(a.at(10), a.at(11));
}

TEST(FrameStates, FramesThatReadDifferentFilesDiffer) {
  const json scene = json::parse(R"({"media": {"s": {"file": "assets/f/smoke.##.vdb"}}})");
  const auto states = frame_states(scene, spec_of({1, 2, 3}, {{"assets/f/smoke.01.vdb", "x"},
                                                              {"assets/f/smoke.02.vdb", "y"},
                                                              {"assets/f/smoke.03.vdb", "x"}}));
  ASSERT_EQ(states.size(), 3u);
  EXPECT_NE(states.at(1), states.at(2));
  EXPECT_EQ(states.at(1), states.at(3));  // same document, same bytes
}

TEST(FrameStates, UnderAShutterTheMotionAroundTheFrameCounts) {
  // Held at frames 2 and 3, but frame 2's shutter [1.5, 2] sees the fov change.
  const json scene = json::parse(
      R"({"render": {"shutter": [-0.5, 0]}, "camera": {"fov": {"keys": [[1.5, 30], [2, 40]]}}})");
  const auto states = frame_states(scene, spec_of({2, 3, 4}, {}));
  EXPECT_NE(states.at(2), states.at(3));
  EXPECT_EQ(states.at(3), states.at(4));
  json sharp = scene;
  sharp["render"].erase("shutter");
  const auto still = frame_states(sharp, spec_of({2, 3}, {}));
  EXPECT_EQ(still.at(2), still.at(3));
}

TEST(FrameStates, NoStatesWhenAFrameCannotBeTold) {
  const json seq = json::parse(R"({"media": {"s": {"file": "assets/smoke.#.vdb"}}})");
  EXPECT_TRUE(frame_states(seq, spec_of({1, 2}, {{"assets/smoke.1.vdb", "x"}})).empty());
  const json bad = json::parse(R"({"camera": {"fov": {"keys": []}}})");
  EXPECT_TRUE(frame_states(bad, spec_of({1}, {})).empty());
}

}  // namespace
}  // namespace vesper

namespace vesper {
namespace {

TEST(FrameAssets, ATaskNeedsItsOwnFrameOfEachSequenceAndEverythingElse) {
  const json scene = json::parse(R"({"shapes": [{"file": "assets/x-cube.obj"}],
      "media": {"s": {"file": "assets/f/smoke.##.vdb"}}})");
  const std::vector<Asset> all = {
      {"assets/x-cube.obj", "c"},      {"assets/f/smoke.01.vdb", "1"},
      {"assets/f/smoke.02.vdb", "2"},  {"assets/f/smoke.103.vdb", "3"},
      {"assets/f/smoke.x.vdb", "odd"}, {"assets/g/smoke.01.vdb", "other folder"}};
  EXPECT_EQ(frame_assets(scene, 2, all),
            (std::vector<Asset>{{"assets/x-cube.obj", "c"},
                                {"assets/f/smoke.02.vdb", "2"},
                                {"assets/f/smoke.x.vdb", "odd"},
                                {"assets/g/smoke.01.vdb", "other folder"}}));
  EXPECT_EQ(frame_assets(scene, 103, all).at(1).blob, "3");
  // A still scene needs every asset.
  EXPECT_EQ(frame_assets(json::parse(R"({"shapes": []})"), 2, all), all);
}

}  // namespace
}  // namespace vesper
