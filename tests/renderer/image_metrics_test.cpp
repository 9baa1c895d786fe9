// firefly_fraction: issue 11's firefly count (luminance > 10x the 5x5
// median), checked on images whose answer is known by construction.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/output/image_metrics.h"

namespace vesper::test {
namespace {

// A smooth RGB gradient between 0.2 and 0.6 in luminance.
LayeredImage gradient(int w, int h) {
  LayeredImage img;
  img.width = w;
  img.height = h;
  img.channels = {"R", "G", "B"};
  img.pixels.resize(size_t(w) * size_t(h) * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (size_t c = 0; c < 3; ++c) img.at(x, y, c) = 0.2f + 0.4f * float(x + y) / float(w + h);
  return img;
}

void scale_pixel(LayeredImage& img, int x, int y, float k) {
  for (size_t c = 0; c < 3; ++c) img.at(x, y, c) *= k;
}

TEST(FireflyFraction, CountsIsolatedSpikesAboveTenTimesTheMedianOnly) {
  LayeredImage img = gradient(40, 30);
  EXPECT_EQ(firefly_fraction(img), 0.0);
  // Five spikes at 11x, one of them in a corner (a clipped 3x3 window).
  const int spikes[5][2] = {{5, 5}, {20, 10}, {33, 25}, {0, 0}, {39, 29}};
  for (const auto& s : spikes) scale_pixel(img, s[0], s[1], 11.f);
  // Two at 9x: bright, but not fireflies by the definition.
  scale_pixel(img, 12, 20, 9.f);
  scale_pixel(img, 28, 4, 9.f);
  EXPECT_DOUBLE_EQ(firefly_fraction(img), 5.0 / (40.0 * 30.0));
}

TEST(FireflyFraction, ABrightRegionIsNotFireflies) {
  LayeredImage img = gradient(40, 30);
  // A 6x6 bright patch: a pixel's 5x5 median is bright where 13 or more of
  // its window lie inside the patch; the corners (9) and their neighbours
  // along the edges (12) see fewer.
  for (int y = 10; y < 16; ++y)
    for (int x = 10; x < 16; ++x) scale_pixel(img, x, y, 50.f);
  int expected = 0;
  for (int y = 10; y < 16; ++y)
    for (int x = 10; x < 16; ++x) {
      const int nx = std::min(15, x + 2) - std::max(10, x - 2) + 1;
      const int ny = std::min(15, y + 2) - std::max(10, y - 2) + 1;
      if (nx * ny <= 12) ++expected;  // the median (13th of 25) is a dark pixel
    }
  EXPECT_EQ(expected, 12);  // 4 corners, 8 edge neighbours
  EXPECT_DOUBLE_EQ(firefly_fraction(img), expected / (40.0 * 30.0));
}

TEST(FireflyFraction, BlackBackgroundNeedsTheFloor) {
  LayeredImage img = gradient(20, 20);
  for (float& v : img.pixels) v = 0.f;
  for (size_t c = 0; c < 3; ++c) img.at(3, 3, c) = 1e-6f;  // below the floor
  for (size_t c = 0; c < 3; ++c) img.at(9, 9, c) = 0.5f;   // a real firefly
  EXPECT_DOUBLE_EQ(firefly_fraction(img), 1.0 / 400.0);
}

}  // namespace
}  // namespace vesper::test
