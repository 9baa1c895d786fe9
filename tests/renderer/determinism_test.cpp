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

TEST(Determinism, SampleRangesMergeBitwiseToTheFullRender) {
  // [0,3) and [3,8) add their exact fixed-point sums to those of [0,8), and
  // the pixels are formed from (sum, count) by the same function.
  SceneDescription d = small_cornell(32, 32, 8);
  d.render.aovs = {Aov::Albedo, Aov::Normal, Aov::Depth};
  const Scene scene = build_scene(d);
  RenderOptions full, first, second;
  full.keep_sums = first.keep_sums = second.keep_sums = true;
  first.sample_end = 3;
  second.sample_begin = 3;
  const RenderResult f = render(scene, full);
  const RenderResult a = render(scene, first);
  const RenderResult b = render(scene, second);
  EXPECT_EQ(a.image.metadata.at("vesper:spp"), "3");
  EXPECT_EQ(b.image.metadata.at("vesper:spp"), "5");
  ASSERT_EQ(a.film.sums.size(), f.image.pixels.size());
  ASSERT_EQ(b.film.sums.size(), f.image.pixels.size());
  std::vector<float> merged(f.image.pixels.size());
  for (size_t i = 0; i < merged.size(); ++i) {
    ASSERT_TRUE(a.film.sums[i] + b.film.sums[i] == f.film.sums[i]) << i;
    merged[i] = exact_mean(a.film.sums[i] + b.film.sums[i], 8);
  }
  EXPECT_EQ(0, std::memcmp(merged.data(), f.image.pixels.data(), merged.size() * sizeof(float)));
  // And a range is not the full render (the test can fail).
  EXPECT_NE(a.image.pixels, f.image.pixels);
}

TEST(Determinism, KeepingTheSumsDoesNotChangeTheImage) {
  const Scene scene = build_scene(small_cornell(16, 16, 4));
  RenderOptions with;
  with.keep_sums = true;
  const RenderResult a = render(scene), b = render(scene, with);
  EXPECT_TRUE(a.film.sums.empty());
  EXPECT_EQ(b.film.sums.size(), b.image.pixels.size());
  EXPECT_EQ(a.image.pixels, b.image.pixels);
  for (size_t i = 0; i < b.film.sums.size(); ++i)
    ASSERT_EQ(exact_mean(b.film.sums[i], 4), b.image.pixels[i]);
}

TEST(Determinism, RefusesRangesLongerThanTheExactSumsHold) {
  const Scene scene = build_scene(small_cornell(4, 4, 1));
  RenderOptions o;
  o.sample_end = int(kMaxExactSamples) + 1;
  EXPECT_THROW(render(scene, o), std::invalid_argument);
}

}  // namespace
}  // namespace vesper::test
