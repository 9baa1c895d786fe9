// `vesper render --frames`: a range of an animated scene, each frame as
// `vesper render --frame N` renders it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "../common/cli_runner.h"
#include "renderer/output/exr_io.h"

namespace fs = std::filesystem;

namespace {

using vesper::test::RunResult;

class FramesCli : public vesper::test::CliTest {
 protected:
  FramesCli() : CliTest("render") {}

  // A lit triangle from `mesh` and a sphere, the camera and the light keyed.
  fs::path write_shot(const std::string& mesh) {
    nlohmann::json doc = nlohmann::json::parse(R"({
      "format": "vesper-scene/1",
      "camera": {"type": "perspective", "from": {"keys": [[1, [0, 0, 4]], [3, [1, 0.5, 4]]]},
                 "to": [0, 0, 0], "up": [0, 1, 0], "fov": {"keys": [[1, 40], [3, 30]], "interp": "smooth"}},
      "film": {"width": 12, "height": 8},
      "render": {"spp": 2, "seed": 5},
      "materials": {"m": {"type": "diffuse", "albedo": {"keys": [[1, [0.8, 0.8, 0.8]], [3, [0.8, 0.2, 0.2]]]}}},
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.6, "material": "m"},
                 {"type": "mesh", "file": "", "material": "m"}],
      "lights": [{"type": "point", "position": [2, 2, 3], "intensity": {"keys": [[1, [9, 9, 9]], [3, [3, 3, 3]]]}}]
    })");
    doc["shapes"][1]["file"] = mesh;
    for (int f = 1; f <= 3; ++f)
      std::ofstream(dir_ / ("tri." + std::to_string(f) + ".obj"))
          << "v -1 -1 -1\nv " << 0.3 * f << " -1 -1\nv 0 1 -1\nf 1 2 3\n";
    const fs::path scene = dir_ / "shot.json";
    std::ofstream(scene) << doc.dump(2);
    return scene;
  }
};

// Metadata that differs between two renders of the same frame: the time taken.
void expect_same_frame(const vesper::LayeredImage& a, const vesper::LayeredImage& b) {
  EXPECT_EQ(a.pixels, b.pixels);
  auto ma = a.metadata, mb = b.metadata;
  ma.erase("vesper:render_seconds");
  mb.erase("vesper:render_seconds");
  EXPECT_EQ(ma, mb);
}

TEST_F(FramesCli, EachFrameOfARangeIsBitwiseItsOwnRender) {
  const fs::path scene = write_shot("tri.#.obj");
  const RunResult r = run(scene.string() + " --frames 1-3 -o " + (dir_ / "shot.####.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, (dir_ / "shot.0001.exr").string() + "\n" + (dir_ / "shot.0002.exr").string() +
                       "\n" + (dir_ / "shot.0003.exr").string() + "\n");
  for (int f = 1; f <= 3; ++f) {
    SCOPED_TRACE(f);
    const fs::path one = dir_ / ("one." + std::to_string(f) + ".exr");
    ASSERT_EQ(
        run(scene.string() + " --frame " + std::to_string(f) + " -q -o " + one.string()).exit_code,
        0);
    expect_same_frame(vesper::read_exr(dir_ / ("shot.000" + std::to_string(f) + ".exr")),
                      vesper::read_exr(one));
  }
  const auto f1 = vesper::read_exr(dir_ / "shot.0001.exr");
  const auto f2 = vesper::read_exr(dir_ / "shot.0002.exr");
  EXPECT_NE(f1.pixels, f2.pixels);
  EXPECT_NE(f1.metadata.at("vesper:scene_hash"), f2.metadata.at("vesper:scene_hash"));
  EXPECT_EQ(f2.metadata.at("vesper:frame"), "2");
}

TEST_F(FramesCli, AStepTakesEveryNthFrame) {
  const fs::path scene = write_shot("tri.1.obj");
  const RunResult r = run(scene.string() + " --frames 1-3x2 -q -o " + (dir_ / "s.##.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "s.01.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "s.02.exr"));
  EXPECT_TRUE(fs::exists(dir_ / "s.03.exr"));
}

TEST_F(FramesCli, UsageErrorsComeBeforeAnyFrame) {
  const fs::path scene = write_shot("tri.1.obj");
  RunResult r = run(scene.string() + " --frames 1-3 -o " + (dir_ / "shot.exr").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("frame pattern ('#')"), std::string::npos) << r.err;
  r = run(scene.string() + " --frames 3-1 -o " + (dir_ / "shot.####.exr").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
  r = run(scene.string() + " --frame 2 --frames 1-3 -o " + (dir_ / "shot.####.exr").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "shot.0001.exr"));
  // One frame needs no pattern.
  EXPECT_EQ(run(scene.string() + " --frames 2 -q -o " + (dir_ / "two.exr").string()).exit_code, 0);
}

TEST_F(FramesCli, AFailingFrameIsNamedAndTheFramesBeforeItStay) {
  const fs::path scene = write_shot("tri.#.obj");
  fs::remove(dir_ / "tri.3.obj");
  const RunResult r = run(scene.string() + " --frames 1-4 -q -o " + (dir_ / "f.#.exr").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("frame 3 (3 of 4) failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("tri.3.obj"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "f.1.exr"));
  EXPECT_TRUE(fs::exists(dir_ / "f.2.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "f.3.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "f.4.exr"));
}

}  // namespace
