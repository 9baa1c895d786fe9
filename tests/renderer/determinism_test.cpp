// A pixel's samples depend only on (seed, pixel, sample index).
#include <gtest/gtest.h>

#include <cstring>

#include "renderer/render/render.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

TEST(Determinism, BitwiseIdenticalForOneAndTwoThreads) {
  SceneDescription d = small_cornell(48, 40, 8);
  d.render.aovs = {Aov::Albedo, Aov::Normal, Aov::Depth};
  const Scene scene = build_scene(d);
  RenderOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const RenderResult a = render(scene, one);
  const RenderResult b = render(scene, two);
  ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
  EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(),
                           a.image.pixels.size() * sizeof(float)));
}

TEST(Determinism, DifferentSeedsGiveDifferentImages) {
  const Scene scene = build_scene(small_cornell(16, 16, 4));
  RenderOptions a, b;
  a.seed = 1;
  b.seed = 2;
  EXPECT_NE(render(scene, a).image.pixels, render(scene, b).image.pixels);
}

TEST(Determinism, SampleRangesMergeToTheFullEstimate) {
  // [0,3) and [3,8) weighted by sample count equal [0,8) up to float rounding
  // of the stored means: the same samples are summed.
  const Scene scene = build_scene(small_cornell(32, 32, 8));
  RenderOptions full, first, second;
  first.sample_end = 3;
  second.sample_begin = 3;
  const RenderResult f = render(scene, full);
  const RenderResult a = render(scene, first);
  const RenderResult b = render(scene, second);
  EXPECT_EQ(a.image.metadata.at("vesper:spp"), "3");
  EXPECT_EQ(b.image.metadata.at("vesper:spp"), "5");
  double max_rel = 0;
  for (size_t i = 0; i < f.image.pixels.size(); ++i) {
    const double merged = (3.0 * a.image.pixels[i] + 5.0 * b.image.pixels[i]) / 8.0;
    const double ref = f.image.pixels[i];
    max_rel = std::max(max_rel, std::abs(merged - ref) / std::max(std::abs(ref), 1e-3));
  }
  EXPECT_LT(max_rel, 1e-6);
  // And a range is not the full render (the test can fail).
  EXPECT_NE(a.image.pixels, f.image.pixels);
}

}  // namespace
}  // namespace vesper::test
