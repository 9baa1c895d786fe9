// Per-frame files: a run of '#' in a scene's `file` is the frame the scene is
// loaded at (VDB sequences, meshes, environment images), and the scene hash
// is of the files that frame reads.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <variant>

#include <OpenImageIO/imageio.h>

#include "renderer/scene/scene_loader.h"
#include "tests/renderer/minimal_scene.h"
#include "tests/renderer/vdb_fixtures.h"

namespace vesper {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

SceneDescription at_frame(const json& doc, const fs::path& file, double frame) {
  return parse_scene(doc, file, SceneLoadOptions{.frame = frame});
}

json smoke_scene(const std::string& file) {
  json doc = test::minimal_scene();
  doc["media"] = {{"smoke", {{"type", "vdb"}, {"file", file}}}};
  return doc;
}

// A cube of `value` (frames differ by their value).
void write_smoke(const test::TempDir& dir, const std::string& name, float value) {
  test::write_volume(dir, name, test::make_volume(4, 4, 4, [=](int, int, int) { return value; }));
}

TEST(SceneFrameFiles, AVdbSequenceLoadsTheFrameItIsLoadedAt) {
  test::TempDir dir;
  write_smoke(dir, "smoke.0001.vdb", 1);
  write_smoke(dir, "smoke.0002.vdb", 2);
  const json doc = smoke_scene("smoke.####.vdb");
  const SceneDescription f1 = at_frame(doc, dir / "shot.json", 1);
  const SceneDescription f2 = at_frame(doc, dir / "shot.json", 2);
  const auto& m1 = std::get<VdbMediumDesc>(f1.media.at(0).medium);
  const auto& m2 = std::get<VdbMediumDesc>(f2.media.at(0).medium);
  EXPECT_EQ(m1.file, (dir / "smoke.0001.vdb").string());
  EXPECT_EQ(m2.file, (dir / "smoke.0002.vdb").string());
  EXPECT_FLOAT_EQ(m1.density->max_value(), 1);
  EXPECT_FLOAT_EQ(m2.density->max_value(), 2);
  // Frames with different files hash differently; the hash is of the file's bytes.
  EXPECT_NE(f1.content_hash, f2.content_hash);
  // (a copy: OpenVDB writes a random UUID into every file it writes)
  fs::copy_file(dir / "smoke.0001.vdb", dir / "smoke.0003.vdb");
  EXPECT_EQ(at_frame(doc, dir / "shot.json", 3).content_hash, f1.content_hash);
}

TEST(SceneFrameFiles, AMissingFrameNamesTheFileThePatternAndTheJsonPath) {
  test::TempDir dir;
  write_smoke(dir, "smoke.0001.vdb", 1);
  try {
    at_frame(smoke_scene("smoke.####.vdb"), dir / "shot.json", 12);
    FAIL() << "a missing frame was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.json_path(), "/media/smoke/file");
    const std::string what = e.what();
    EXPECT_NE(what.find((dir / "smoke.0012.vdb").string()), std::string::npos) << what;
    EXPECT_NE(what.find("'smoke.####.vdb'"), std::string::npos) << what;
    EXPECT_NE(what.find("frame 12"), std::string::npos) << what;
  }
}

TEST(SceneFrameFiles, MeshesAndEnvironmentImagesTakeFramePatternsToo) {
  test::TempDir dir;
  for (int f = 1; f <= 2; ++f) {
    std::ofstream(dir / ("tri." + std::to_string(f) + ".obj"))
        << "v " << f << " 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n";
    const fs::path image = dir / ("sky.0" + std::to_string(f) + ".exr");
    auto out = OIIO::ImageOutput::create(image.string());
    ASSERT_TRUE(out && out->open(image.string(), OIIO::ImageSpec(2, 1, 3, OIIO::TypeDesc::FLOAT)));
    const float px[6] = {float(f), 0, 0, float(f), 0, 0};
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px));
    out->close();
  }
  json doc = test::minimal_scene();
  doc["shapes"] = json::parse(R"([{"type": "mesh", "file": "tri.#.obj", "material": "m"}])");
  doc["lights"] = json::parse(R"([{"type": "environment", "file": "sky.##.exr"}])");
  for (int f = 1; f <= 2; ++f) {
    const SceneDescription s = at_frame(doc, dir / "shot.json", f);
    EXPECT_EQ(std::get<MeshShapeDesc>(s.shapes.at(0).geometry).positions.at(0).x, f);
    const auto& env = std::get<EnvironmentLightDesc>(s.lights.at(0).light);
    EXPECT_EQ(env.file, (dir / ("sky.0" + std::to_string(f) + ".exr")).string());
    EXPECT_EQ(env.image->pixels.at(0).r, float(f));
  }
}

TEST(SceneFrameFiles, AStillFileIsReadAtEveryFrame) {
  test::TempDir dir;
  write_smoke(dir, "smoke.vdb", 1);
  const json doc = smoke_scene("smoke.vdb");
  EXPECT_EQ(at_frame(doc, dir / "shot.json", 1).content_hash,
            at_frame(doc, dir / "shot.json", 9).content_hash);
}

}  // namespace
}  // namespace vesper
