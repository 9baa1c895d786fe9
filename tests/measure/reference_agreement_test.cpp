// Two references of the same picture agree; a scene whose light is 30 %
// brighter in one renderer, or whose left half differs, is flagged.
#include <gtest/gtest.h>

#include <random>

#include "measure/reference_agreement.h"
#include "synthetic_images.h"

namespace vesper::measure {
namespace {

TEST(ReferenceAgreement, TwoNoisyRendersOfOnePictureAgree) {
  std::mt19937_64 rng(3);
  const LayeredImage truth = synth::truth_image(64, 48);
  const ReferenceAgreement a =
      compare_references(synth::noisy(truth, 0.05, rng), synth::noisy(truth, 0.05, rng));
  EXPECT_FALSE(a.flagged) << (a.reasons.empty() ? "" : a.reasons[0]);
  EXPECT_NEAR(a.mean_ratio, 1.0, 0.01);
  EXPECT_EQ(a.blocks, 4 * 3);
  EXPECT_LE(a.block_min, a.block_p05);
  EXPECT_LE(a.block_p05, a.block_p95);
  EXPECT_LE(a.block_p95, a.block_max);
}

TEST(ReferenceAgreement, AnExactScaleShowsInEveryRatio) {
  const LayeredImage truth = synth::truth_image(40, 40);  // partial edge blocks too
  LayeredImage brighter = truth;
  for (float& v : brighter.pixels) v *= 1.3f;
  const ReferenceAgreement a = compare_references(brighter, truth);
  EXPECT_NEAR(a.mean_ratio, 1.3, 1e-5);
  EXPECT_NEAR(a.block_min, 1.3, 1e-5);
  EXPECT_NEAR(a.block_max, 1.3, 1e-5);
  EXPECT_EQ(a.blocks, 9);
  EXPECT_TRUE(a.flagged);
  EXPECT_EQ(a.reasons.size(), 3u);  // the mean and both percentiles
}

TEST(ReferenceAgreement, ALocalDifferenceShowsInTheBlocksNotTheMean) {
  const LayeredImage truth = synth::rgb_image(160, 16, 1.0f);  // 10 blocks in a row
  LayeredImage changed = truth;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (size_t c = 0; c < 3; ++c) changed.at(x, y, c) = 1.4f;  // one block of ten
  const ReferenceAgreement a = compare_references(changed, truth);
  EXPECT_NEAR(a.mean_ratio, 1.04, 1e-6);  // inside [0.95, 1.053]
  EXPECT_NEAR(a.block_max, 1.4, 1e-6);
  EXPECT_NEAR(a.block_p95, 1.4, 1e-6);  // nearest rank: the 10th of 10
  EXPECT_TRUE(a.flagged);
  ASSERT_EQ(a.reasons.size(), 1u);
  EXPECT_NE(a.reasons[0].find("95th"), std::string::npos) << a.reasons[0];
}

TEST(ReferenceAgreement, DarkBlocksAreLeftOut) {
  LayeredImage a = synth::rgb_image(32, 16, 0.0f), b = synth::rgb_image(32, 16, 0.0f);
  for (int y = 0; y < 16; ++y)
    for (int x = 16; x < 32; ++x)
      for (size_t c = 0; c < 3; ++c) a.at(x, y, c) = b.at(x, y, c) = 0.5f;
  const ReferenceAgreement r = compare_references(a, b);
  EXPECT_EQ(r.blocks, 1);
  EXPECT_FALSE(r.flagged);
  EXPECT_THROW(compare_references(a, synth::rgb_image(16, 16)), std::invalid_argument);
}

}  // namespace
}  // namespace vesper::measure
