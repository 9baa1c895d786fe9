// The example scenes load and render finite images; the smoke scene uses the
// real third-party smoke simulation from ../shared/data (skipped when absent).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "renderer/render/render.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/volume/cloud.h"
#include "renderer/volume/vdb_io.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {

const fs::path kScenes = fs::path(VESPER_SOURCE_DIR) / "scenes";

// Renders at a small size; returns the mean luminance.
double render_small(SceneDescription d, RenderStats* stats = nullptr) {
  d.film.width = 32;
  d.film.height = 32;
  RenderOptions o;
  o.spp = 4;
  const RenderResult r = render(build_scene(d), o);
  double sum = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(r.image.at(x, y, size_t(c))));
      sum += 0.2126 * r.image.at(x, y, 0) + 0.7152 * r.image.at(x, y, 1) +
             0.0722 * r.image.at(x, y, 2);
    }
  EXPECT_EQ(r.stats.nonfinite_samples, 0u);
  if (stats) *stats = r.stats;
  return sum / (32 * 32);
}

TEST(ExampleScenes, CornellBoxRenders) {
  EXPECT_GT(render_small(load_scene(kScenes / "cornell/scene.json")), 0.01);
}

TEST(ExampleScenes, MotionBlurRendersAndTheShutterMatters) {
  const SceneDescription d =
      load_scene(kScenes / "motion-blur/scene.json", SceneLoadOptions{.frame = 4});
  EXPECT_EQ(d.motion_times.size(), 9u);
  EXPECT_EQ(d.camera_steps.size(), 9u);
  SceneDescription still = d;
  still.motion_times.clear();
  still.camera_steps.clear();
  for (ShapeDesc& s : still.shapes) s.steps.clear();
  EXPECT_NE(render_small(d), render_small(still));
}

TEST(ExampleScenes, FogShaftsRendersAndTheFogMatters) {
  const SceneDescription d = load_scene(kScenes / "fog-shafts/scene.json");
  ASSERT_EQ(d.media.size(), 1u);
  SceneDescription clear = d;
  clear.media.clear();
  EXPECT_NE(render_small(d), render_small(clear));
}

TEST(ExampleScenes, RealSmokeSimulationLoadsAndRenders) {
  const fs::path smoke = fs::path(VESPER_SOURCE_DIR) / "../shared/data/smoke.vdb";
  if (!fs::exists(smoke))
    GTEST_SKIP() << "shared smoke data not found at " << smoke << "; skipping";
  const SceneDescription d = load_scene(kScenes / "smoke/scene.json");
  ASSERT_EQ(d.media.size(), 1u);
  const auto& v = std::get<VdbMediumDesc>(d.media[0].medium);
  EXPECT_FALSE(v.density->active_box().empty());
  EXPECT_GT(v.density->max_value(), 1.f);
  SceneDescription clear = d;
  clear.media.clear();
  // The smoke sits in the middle of the view: with it the image must change.
  EXPECT_NE(render_small(d), render_small(clear));
}

TEST(ExampleScenes, ProceduralCloudSceneRendersFromAGeneratedVdb) {
  const test::TempDir dir("cloud");
  CloudParams p;
  p.resolution = 48;
  p.voxel_size = 2.56 / 48;
  write_vdb_fog_volume(generate_cloud(p), "density", dir / "cloud.vdb");
  fs::copy_file(kScenes / "cloud/scene.json", dir / "scene.json");
  const SceneDescription d = load_scene(dir / "scene.json");
  EXPECT_GT(render_small(d), 0.0);
}

// The animated example: its cloud sequence generated as `vesper vdb cloud
// --frames` writes it (smaller), loaded at two frames of the shot.
TEST(ExampleScenes, TheShotLoadsAtTwoFramesAndTheyDiffer) {
  const test::TempDir dir("shot");
  CloudParams p;
  p.resolution = 32;
  p.voxel_size = 2.56 / 32;
  for (const int f : {1, 24}) {
    p.time = f - 1;
    write_vdb_fog_volume(generate_cloud(p), "density",
                         dir / (f == 1 ? "cloud.0001.vdb" : "cloud.0024.vdb"));
  }
  fs::copy_file(kScenes / "shot/scene.json", dir / "scene.json");
  const SceneDescription first = load_scene(dir / "scene.json", {.frame = 1});
  const SceneDescription last = load_scene(dir / "scene.json", {.frame = 24});
  EXPECT_NE(first.camera.from.x, last.camera.from.x);
  EXPECT_NE(first.content_hash, last.content_hash);
  EXPECT_NE(std::get<VdbMediumDesc>(first.media.at(0).medium).file,
            std::get<VdbMediumDesc>(last.media.at(0).medium).file);
  EXPECT_NE(render_small(first), render_small(last));
  // A frame whose cloud was not generated is named.
  EXPECT_THROW(load_scene(dir / "scene.json", {.frame = 12}), SceneError);
}

}  // namespace
}  // namespace vesper
