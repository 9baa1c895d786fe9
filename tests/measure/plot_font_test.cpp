// The plot's fallback digit font draws numbers where asked and nothing for
// letters it does not have; the TrueType path draws text.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "measure/plot_font.h"

namespace vesper::measure {
namespace {

// Inked pixels' bounding box: {x0, y0, x1, y1}, or all -1 when none.
std::array<int, 4> ink_box(const OIIO::ImageBuf& img) {
  std::array<int, 4> box{-1, -1, -1, -1};
  for (int y = 0; y < img.spec().height; ++y)
    for (int x = 0; x < img.spec().width; ++x) {
      if (img.getchannel(x, y, 0, 0) > 0.5f) continue;  // white background
      if (box[0] < 0) box = {x, y, x, y};
      box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
    }
  return box;
}

OIIO::ImageBuf white() {
  OIIO::ImageBuf img(OIIO::ImageSpec(120, 40, 3, OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::fill(img, {1.0f, 1.0f, 1.0f});
  return img;
}

TEST(PlotFont, DigitFontDrawsNumbersOnTheBaseline) {
  OIIO::ImageBuf img = white();
  // size 14: glyph pixels of 2, glyphs 6 wide + 2 apart, 10 high above the baseline.
  PlotFont::digits_only().draw(img, 10, 30, "1e-3", 14, {0, 0, 0});
  const auto box = ink_box(img);
  EXPECT_EQ(box[1], 20);
  EXPECT_EQ(box[3], 29);
  EXPECT_GE(box[0], 10);
  EXPECT_LE(box[2], 10 + 4 * 8);
}

TEST(PlotFont, DigitFontRightAlignsAndSkipsLetters) {
  OIIO::ImageBuf img = white();
  PlotFont::digits_only().draw(img, 100, 30, "10", 14, {0, 0, 0}, TextAlign::Right);
  EXPECT_LE(ink_box(img)[2], 99);
  EXPECT_GE(ink_box(img)[0], 100 - 16);
  OIIO::ImageBuf letters = white();
  PlotFont::digits_only().draw(letters, 10, 30, "MSR", 14, {0, 0, 0});  // no digit-font letters
  EXPECT_EQ(ink_box(letters)[0], -1);
}

TEST(PlotFont, TrueTypeDrawsTextWhenTheFontIsThere) {
  const PlotFont font;
  if (!font.has_truetype()) GTEST_SKIP() << "no DejaVu Sans (fonts-dejavu-core)";
  OIIO::ImageBuf img = white();
  font.draw(img, 10, 30, "relMSE", 14, {0, 0, 0});
  EXPECT_GE(ink_box(img)[0], 0);
}

}  // namespace
}  // namespace vesper::measure
