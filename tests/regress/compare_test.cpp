// compare_frames on synthetic images: which layers are compared, how channel
// changes, resolution changes, layers without variance and small changes are
// judged, and what the reasons say.
#include <gtest/gtest.h>

#include "regress/compare.h"
#include "synthetic_images.h"

namespace vesper::regress {
namespace {

using test::scale_region;
using test::synthetic_image;
using test::SyntheticLayer;

std::string all_reasons(const SceneResult& r) {
  std::string s;
  for (const std::string& line : r.reasons) s += line + "\n";
  for (const LayerResult& l : r.layers)
    for (const std::string& line : l.reasons) s += "[" + l.layer + "] " + line + "\n";
  return s;
}

const LayerResult& layer(const SceneResult& r, const std::string& name) {
  for (const LayerResult& l : r.layers)
    if (l.layer == name) return l;
  throw std::runtime_error("no layer " + name);
}

const std::vector<SyntheticLayer> kLayers = {{"beauty"}, {"fog", 0.2, 0.001}};

TEST(CompareFrames, SameDistributionPassesAndSaysHowStrongThePassWas) {
  const SceneResult r = compare_frames(synthetic_image(64, 64, kLayers, 1),
                                       synthetic_image(64, 64, kLayers, 2), nullptr, {});
  EXPECT_EQ(r.verdict, Verdict::Pass) << all_reasons(r);
  ASSERT_EQ(r.layers.size(), 2u);
  const LayerResult& b = layer(r, "beauty");
  EXPECT_TRUE(b.has_variance);
  EXPECT_EQ(b.tiles, 16);
  EXPECT_EQ(b.tiles_x * b.tiles_y, 16);
  EXPECT_EQ(b.tile_z.size(), 16u);
  // sd of a tile's difference: sqrt(2 * 0.01 / 256) = 0.00884, 1.77 % of 0.5;
  // the first Holm step over 16 tiles + 5 blocks needs |Z| >= 4.58.
  EXPECT_NEAR(b.min_detectable_change, 4.58 * 0.0177, 0.01);
  EXPECT_NEAR(b.frame_detectable_change, b.min_detectable_change / 4, 0.005);
  EXPECT_NE(b.reasons[0].find("no change beyond noise in 16 tiles"), std::string::npos)
      << b.reasons[0];
  EXPECT_TRUE(r.reasons.empty());  // the scene lists only what did not pass
}

TEST(CompareFrames, AChangedTileIsARegionNamedInTheReasons) {
  LayeredImage fresh = synthetic_image(64, 64, kLayers, 2);
  scale_region(fresh, "fog.", 1.2, 16, 32, 32, 48);
  const SceneResult r = compare_frames(synthetic_image(64, 64, kLayers, 1), fresh, nullptr, {});
  EXPECT_EQ(r.verdict, Verdict::Regressed);
  EXPECT_EQ(layer(r, "beauty").verdict, Verdict::Pass);
  const LayerResult& fog = layer(r, "fog");
  ASSERT_FALSE(fog.worst.empty());
  EXPECT_EQ(fog.worst[0].x, 16);
  EXPECT_EQ(fog.worst[0].y, 32);
  EXPECT_EQ(fog.worst[0].width, 16);
  EXPECT_NEAR(fog.worst[0].relative_change, 0.2, 0.02);
  EXPECT_GT(fog.worst[0].z, 10);  // 0.04 / sqrt(2 * 0.001 / 256) = 14
  EXPECT_EQ(fog.significant_tiles, 1);
  EXPECT_EQ(fog.tile_z[2 * 4 + 1], float(fog.worst[0].z));
  std::vector<uint8_t> significant(16, 0);
  significant[2 * 4 + 1] = 1;
  EXPECT_EQ(fog.tile_significant, significant);
  ASSERT_EQ(r.reasons.size(), 1u) << all_reasons(r);
  EXPECT_EQ(r.reasons[0].rfind("fog: brighter in 1 tile and 1 larger block, worst +2", 0), 0u)
      << r.reasons[0];
  EXPECT_NE(r.reasons[0].find("at x 16-31 y 32-47 (Z "), std::string::npos) << r.reasons[0];
}

TEST(CompareFrames, MinRelativeChangeIgnoresSmallSignificantChanges) {
  LayeredImage fresh = synthetic_image(64, 64, kLayers, 2);
  scale_region(fresh, "fog.", 1.2, 16, 32, 32, 48);
  Thresholds t;
  t.min_relative_change = 0.5;
  const SceneResult r = compare_frames(synthetic_image(64, 64, kLayers, 1), fresh, nullptr, t);
  EXPECT_EQ(r.verdict, Verdict::Pass) << all_reasons(r);
  EXPECT_EQ(layer(r, "fog").significant_tiles, 1);
  EXPECT_EQ(layer(r, "fog").tile_significant, std::vector<uint8_t>(16, 0));  // does not count
  EXPECT_NE(all_reasons(r).find("less than min_relative_change 50 %: ignored"), std::string::npos)
      << all_reasons(r);
}

TEST(CompareFrames, AWideFaintChangeShowsInTheBlocks) {
  LayeredImage fresh = synthetic_image(64, 64, kLayers, 2);
  scale_region(fresh, "", 1.03, 0, 0, 64, 64);  // 3 %: Z ~1.7 per tile, ~6.8 over the frame
  const SceneResult r = compare_frames(synthetic_image(64, 64, kLayers, 1), fresh, nullptr, {});
  const LayerResult& b = layer(r, "beauty");
  EXPECT_EQ(b.verdict, Verdict::Regressed) << all_reasons(r);
  ASSERT_FALSE(b.worst.empty());
  EXPECT_EQ(b.worst[0].width, 64);  // the frame
  EXPECT_NE(all_reasons(r).find("larger block"), std::string::npos) << all_reasons(r);
}

TEST(CompareFrames, RequestedLayersOnlyAndUnknownLayersAreErrors) {
  const std::vector<std::string> fog = {"fog"}, ghost = {"ghost"};
  const LayeredImage g = synthetic_image(32, 32, kLayers, 1),
                     f = synthetic_image(32, 32, kLayers, 2);
  const SceneResult only = compare_frames(g, f, &fog, {});
  ASSERT_EQ(only.layers.size(), 1u);
  EXPECT_EQ(only.layers[0].layer, "fog");
  const SceneResult none = compare_frames(g, f, &ghost, {});
  EXPECT_EQ(none.verdict, Verdict::Error);
  EXPECT_NE(none.reasons[0].find("ghost: no layer \"ghost\" in the golden or the new render "
                                 "(golden layers: beauty, fog; new: beauty, fog)"),
            std::string::npos)
      << none.reasons[0];
}

TEST(CompareFrames, AddedAndMissingLayersAndChannelsRegress) {
  const LayeredImage g = synthetic_image(32, 32, kLayers, 1);
  const LayeredImage beauty_only = synthetic_image(32, 32, {{"beauty"}}, 2);
  const SceneResult missing = compare_frames(g, beauty_only, nullptr, {});
  EXPECT_EQ(missing.verdict, Verdict::Regressed);
  EXPECT_EQ(layer(missing, "fog").verdict, Verdict::Regressed);
  EXPECT_EQ(missing.channels_missing.size(), 6u);  // fog.R/G/B and fog.variance.R/G/B
  EXPECT_NE(all_reasons(missing).find("fog: missing in the new render"), std::string::npos);
  const SceneResult added = compare_frames(beauty_only, g, nullptr, {});
  EXPECT_EQ(added.verdict, Verdict::Regressed);
  EXPECT_EQ(added.channels_added.size(), 6u);
  EXPECT_NE(all_reasons(added).find("fog: not in the golden"), std::string::npos);
  // The fog's variance gone: fog regresses for its channels and is compared without noise model.
  const LayeredImage no_var = synthetic_image(32, 32, {{"beauty"}, {"fog", 0.2, 0.001, false}}, 2);
  const SceneResult r = compare_frames(g, no_var, nullptr, {});
  EXPECT_EQ(layer(r, "fog").verdict, Verdict::Regressed);
  EXPECT_FALSE(layer(r, "fog").has_variance);
  EXPECT_NE(all_reasons(r).find("fog: channels missing: fog.variance.R, fog.variance.G, "
                                "fog.variance.B"),
            std::string::npos)
      << all_reasons(r);
}

TEST(CompareFrames, LayersWithoutVarianceGetNanAndHistogramChecks) {
  const std::vector<SyntheticLayer> layers = {{"beauty"}, {"albedo", 0.5, 1e-4, false}};
  const LayeredImage g = synthetic_image(32, 32, layers, 1);
  LayeredImage f = synthetic_image(32, 32, layers, 2);
  const SceneResult same = compare_frames(g, f, nullptr, {});
  EXPECT_EQ(same.verdict, Verdict::Pass) << all_reasons(same);
  const LayerResult& a = layer(same, "albedo");
  EXPECT_FALSE(a.has_variance);
  EXPECT_EQ(a.tiles, 0);
  EXPECT_NE(a.reasons[0].find("no variance channels (albedo.variance.R/G/B)"), std::string::npos);
  scale_region(f, "albedo.", 1.5, 0, 0, 32, 32);  // 0.58 stops brighter
  const SceneResult brighter = compare_frames(g, f, nullptr, {});
  EXPECT_EQ(layer(brighter, "albedo").verdict, Verdict::Regressed);
  EXPECT_NEAR(layer(brighter, "albedo").histogram_distance, std::log2(1.5), 0.05);
  EXPECT_NE(all_reasons(brighter).find("albedo: luminosity histogram moved 0.5"), std::string::npos)
      << all_reasons(brighter);
}

TEST(CompareFrames, NonRgbLayersAreCheckedForNanOnly) {
  LayeredImage g;
  g.width = g.height = 4;
  g.channels = {"normal.X", "normal.Y", "normal.Z"};
  g.pixels.assign(16 * 3, 0.5f);
  LayeredImage f = g;
  f.at(2, 3, 1) = INFINITY;
  const SceneResult r = compare_frames(g, f, nullptr, {});
  EXPECT_EQ(r.verdict, Verdict::Regressed);
  const LayerResult& n = layer(r, "normal");
  EXPECT_EQ(n.new_nonfinite, 1u);
  EXPECT_EQ(n.golden_nonfinite, 0u);
  EXPECT_NE(all_reasons(r).find("normal: 1 new NaN/Inf pixel (golden 0, new 1), first at (2, 3)"),
            std::string::npos)
      << all_reasons(r);
  EXPECT_NE(all_reasons(r).find("neither RGB nor a single channel"), std::string::npos);
}

TEST(CompareFrames, NanAlreadyInTheGoldenIsNotNew) {
  LayeredImage g = synthetic_image(16, 16, {{"beauty"}}, 1),
               f = synthetic_image(16, 16, {{"beauty"}}, 2);
  g.at(3, 4, 0) = NAN;
  f.at(3, 4, 2) = NAN;
  const SceneResult r = compare_frames(g, f, nullptr, {});
  EXPECT_EQ(r.verdict, Verdict::Pass) << all_reasons(r);
  EXPECT_EQ(layer(r, "beauty").golden_nonfinite, 1u);
  EXPECT_EQ(layer(r, "beauty").new_nonfinite, 1u);
  EXPECT_EQ(layer(r, "beauty").introduced_nonfinite, 0u);
}

TEST(CompareFrames, AResolutionChangeRegressesWithoutComparingLayers) {
  const SceneResult r = compare_frames(synthetic_image(32, 32, kLayers, 1),
                                       synthetic_image(32, 16, kLayers, 2), nullptr, {});
  EXPECT_EQ(r.verdict, Verdict::Regressed);
  EXPECT_TRUE(r.layers.empty());
  EXPECT_EQ(r.reasons[0], "resolution changed from 32x32 to 32x16: not compared");
}

}  // namespace
}  // namespace vesper::regress
