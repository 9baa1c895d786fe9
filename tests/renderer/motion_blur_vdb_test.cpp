// Motion blur of a VDB medium: its keyed transform is sampled over the
// shutter and rays meet its voxels where they are at their time. (The time
// average itself is tested on a moving box medium, motion_blur_test.cpp,
// through the same MediaSet code; here the VDB plumbing.)
#include <gtest/gtest.h>

#include <cstring>

#include <nlohmann/json.hpp>

#include "renderer/render/render.h"
#include "renderer/scene/scene_loader.h"
#include "tests/renderer/vdb_fixtures.h"

namespace vesper {
namespace {

using nlohmann::json;

// A 2 x 2 x 0.2 slab of density 1 (voxels of 0.1) in front of a white
// environment, sliding from x = -2 at frame 1 to 0 at frame 2.
json sliding_vdb_scene(const std::string& file, const json& shutter) {
  json doc = json::parse(R"({
    "format": "vesper-scene/1",
    "camera": {"type": "perspective", "from": [0, 0, 4], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 30},
    "film": {"width": 24, "height": 12},
    "render": {"spp": 16, "max_depth": 2},
    "materials": {"m": {"type": "diffuse"}},
    "shapes": [],
    "lights": [{"type": "environment", "radiance": [1, 1, 1]}],
    "media": {"slab": {"type": "vdb", "sigma_a": [4, 4, 4], "sigma_s": [1, 1, 1],
      "transform": {"translate": {"keys": [[1, [-2, -1, -0.1]], [2, [0, -1, -0.1]]]}}}}
  })");
  doc["media"]["slab"]["file"] = file;
  if (!shutter.is_null()) doc["render"]["shutter"] = shutter;
  return doc;
}

Scene load(const json& doc, double frame) {
  return build_scene(parse_scene(doc, "vdb-motion.json", SceneLoadOptions{.frame = frame}));
}

bool same(const LayeredImage& a, const LayeredImage& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

class MotionBlurVdb : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = test::write_volume(dir_, "slab.vdb",
                               test::make_volume(
                                   20, 20, 2, [](int, int, int) { return 1.f; }, 0.1))
                .string();
  }
  test::VdbTempDir dir_;
  std::string file_;
};

TEST_F(MotionBlurVdb, TheTransformIsSampledOverTheShutter) {
  const SceneDescription d =
      parse_scene(sliding_vdb_scene(file_, {0, 0.5}), "m.json", SceneLoadOptions{.frame = 1});
  ASSERT_EQ(d.motion_times.size(), 2u);
  const auto& v = std::get<VdbMediumDesc>(d.media[0].medium);
  ASSERT_EQ(v.transform_steps.size(), 2u);
  EXPECT_DOUBLE_EQ(v.transform_steps[1].apply_point(Vec3d(0.0)).x, -1.0);
  EXPECT_TRUE(build_scene(d).motion_blur);
}

TEST_F(MotionBlurVdb, AZeroLengthShutterIsTheStillFrameAtThatTime) {
  const Scene instant = load(sliding_vdb_scene(file_, {0.25, 0.25}), 1);
  const Scene still = load(sliding_vdb_scene(file_, json()), 1.25);
  EXPECT_TRUE(same(render(instant).image, render(still).image));
}

TEST_F(MotionBlurVdb, TheBlurDiffersFromBothEndsAndIsDeterministic) {
  const Scene blurred = load(sliding_vdb_scene(file_, {0, 0.5}), 1);
  RenderOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const RenderResult a = render(blurred, one);
  EXPECT_TRUE(same(a.image, render(blurred, two).image));
  EXPECT_EQ(a.stats.nonfinite_samples, 0u);
  EXPECT_FALSE(same(a.image, render(load(sliding_vdb_scene(file_, json()), 1)).image));
  EXPECT_FALSE(same(a.image, render(load(sliding_vdb_scene(file_, json()), 1.5)).image));
}

}  // namespace
}  // namespace vesper
