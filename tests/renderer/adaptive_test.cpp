// Adaptive sampling to a noise target, time limits, and their determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "renderer/output/image_metrics.h"
#include "renderer/output/partial_io.h"
#include "renderer/render/frame.h"
#include "renderer/render/render.h"
#include "renderer/scene/scene_loader.h"
#include "scene_fixtures.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;

// The beauty R, G, B of `img` as a 3-channel image, for relative_mse.
LayeredImage beauty(const LayeredImage& img) {
  LayeredImage out;
  out.width = img.width;
  out.height = img.height;
  out.channels = {"R", "G", "B"};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (size_t c = 0; c < 3; ++c) out.pixels.push_back(img.at(x, y, c));
  return out;
}

double meta_number(const LayeredImage& img, const char* key) {
  return std::stod(img.metadata.at(key));
}

// A render to noise target X has each pixel's estimated relative error (the
// square root of relMSE's own per-pixel term) at most X, so its relMSE is
// about X² or less; 1.5 X² leaves room for the estimates' own noise and the
// reference's. And it must not be far below X² either: then it oversampled.
void expect_noise_target_met(const SceneDescription& d, double target, const char* label) {
  const Scene scene = build_scene(d);
  RenderOptions ref_options;
  ref_options.spp = 4096;
  const LayeredImage ref = beauty(render(scene, ref_options).image);
  RenderOptions o;
  o.noise_target = target;
  o.max_spp = 4096;
  const RenderResult r = render(scene, o);
  const double rel = relative_mse(beauty(r.image), ref);
  EXPECT_LT(rel, 1.5 * target * target) << label;
  EXPECT_GT(rel, target * target / 20) << label;
  EXPECT_EQ(r.image.metadata.at("vesper:stop_reason"), "noise_target") << label;
  EXPECT_LE(meta_number(r.image, "vesper:noise_reached"), target) << label;
  // It sampled unevenly: some pixels stopped early, others went on.
  const int spp = r.image.channel_index("spp");
  ASSERT_GE(spp, 0);
  float lo = 1e30f, hi = 0;
  for (int y = 0; y < r.image.height; ++y)
    for (int x = 0; x < r.image.width; ++x) {
      lo = std::min(lo, r.image.at(x, y, size_t(spp)));
      hi = std::max(hi, r.image.at(x, y, size_t(spp)));
    }
  EXPECT_LT(lo * 2, hi) << label;
  std::printf("%s: target %.3f, relMSE %.3g (target^2 %.3g), spp %g..%g, mean %s\n", label, target,
              rel, target * target, lo, hi, r.image.metadata.at("vesper:spp_mean").c_str());
}

TEST(Adaptive, MeetsTheNoiseTargetOnTheCornellBox) {
  expect_noise_target_met(small_cornell(24, 24, 16), 0.1, "cornell");
}

TEST(Adaptive, MeetsTheNoiseTargetInFog) {
  SceneDescription d = load_scene(fs::path(VESPER_SOURCE_DIR) / "scenes/fog-shafts/scene.json");
  d.film.width = 24;
  d.film.height = 24;
  expect_noise_target_met(d, 0.2, "fog-shafts");
}

TEST(Adaptive, BadSettingsAreErrorsNamingTheField) {
  const Scene scene = build_scene(small_cornell(4, 4, 4));
  auto message = [&](RenderOptions o) -> std::string {
    try {
      render(scene, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(no error)";
  };
  RenderOptions zero, negative, crossed, no_time;
  zero.noise_target = 0;
  negative.noise_target = -0.1;
  crossed.noise_target = 0.1;
  crossed.min_spp = 64;
  crossed.max_spp = 16;
  no_time.time_limit = 0;
  EXPECT_NE(message(zero).find("render.noise_target"), std::string::npos) << message(zero);
  EXPECT_NE(message(negative).find("render.noise_target"), std::string::npos);
  EXPECT_NE(message(crossed).find("render.min_spp"), std::string::npos) << message(crossed);
  EXPECT_NE(message(no_time).find("render.time_limit"), std::string::npos);
}

TEST(Adaptive, SameImageAndCountsForAnyThreadCount) {
  const Scene scene = build_scene(small_cornell(40, 32, 16));
  RenderOptions one, three;
  one.noise_target = three.noise_target = 0.15;
  one.max_spp = three.max_spp = 256;
  one.threads = 1;
  three.threads = 3;
  const RenderResult a = render(scene, one), b = render(scene, three);
  ASSERT_EQ(a.image.channels, b.image.channels);
  ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
  EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(),
                           a.image.pixels.size() * sizeof(float)));
  EXPECT_EQ(a.image.metadata.at("vesper:spp_mean"), b.image.metadata.at("vesper:spp_mean"));
  EXPECT_EQ(a.stats.sampling_passes, b.stats.sampling_passes);
  EXPECT_GT(a.stats.sampling_passes, 1);
}

// A frame split into sample ranges, each sampled adaptively within its range
// (the farm's chunks), merges exactly: sums and per-pixel counts add.
TEST(Adaptive, PartialsOfAdaptiveRangesMergeExactly) {
  const SceneDescription d = small_cornell(24, 16, 16);
  auto part = [&](int begin, int end, const char* label) {
    RenderOptions o;
    o.noise_target = 0.2;
    o.sample_begin = begin;
    o.sample_end = end;
    o.keep_sums = true;
    FrameResult f = render_frame(d, o);
    return make_partial(f.image, std::move(f.film), 128, label);
  };
  const Partial a = part(0, 64, "a"), b = part(64, 128, "b");
  const LayeredImage ab = merge_partials({a, b}), ba = merge_partials({b, a});
  ASSERT_EQ(ab.pixels.size(), ba.pixels.size());
  EXPECT_EQ(0, std::memcmp(ab.pixels.data(), ba.pixels.data(), ab.pixels.size() * sizeof(float)));
  FilmSums both = a.film();
  both.add(b.film());
  const LayeredImage direct = resolve_image(both);
  EXPECT_EQ(0,
            std::memcmp(ab.pixels.data(), direct.pixels.data(), ab.pixels.size() * sizeof(float)));
  // The merged counts are the sums of the parts' counts, and the merged
  // noise is recomputed (lower than either part's).
  const int spp = ab.channel_index("spp");
  const LayeredImage ia = resolve_image(a.film()), ib = resolve_image(b.film());
  for (int y = 0; y < ab.height; ++y)
    for (int x = 0; x < ab.width; ++x)
      ASSERT_EQ(ab.at(x, y, size_t(spp)), ia.at(x, y, size_t(spp)) + ib.at(x, y, size_t(spp)));
  EXPECT_LT(meta_number(ab, "vesper:noise_reached"),
            std::min(std::stod(a.metadata.at("vesper:noise_reached")),
                     std::stod(b.metadata.at("vesper:noise_reached"))));
}

TEST(Adaptive, ATimeLimitStopsAtTheEndOfAPassAndRecordsTheSamples) {
  const Scene scene = build_scene(small_cornell(48, 48, 1 << 20));
  RenderOptions o;
  o.time_limit = 0.4;
  const RenderResult r = render(scene, o);
  EXPECT_EQ(r.image.metadata.at("vesper:stop_reason"), "time_limit");
  EXPECT_GE(r.stats.seconds, 0.4);
  // The whole range would take hours; stopping within a pass or two of the
  // budget is what matters (the last pass is sized to end near it).
  EXPECT_LT(r.stats.seconds, 3.0);
  const double mean = meta_number(r.image, "vesper:spp_mean");
  EXPECT_GT(mean, 4);
  EXPECT_LT(mean, 1 << 20);
  EXPECT_GT(r.stats.sampling_passes, 1);
}

}  // namespace
}  // namespace vesper::test
