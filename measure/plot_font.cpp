#include "measure/plot_font.h"

#include <algorithm>
#include <filesystem>
#include <string_view>

#include <OpenImageIO/imagebufalgo.h>

namespace vesper::measure {
namespace {

constexpr const char* kFontFiles[] = {
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
};

// 3x5 glyphs, one row per 3 bits (top row first, leftmost pixel = bit 2).
struct Glyph {
  char c;
  std::array<unsigned char, 5> rows;
};
constexpr Glyph kGlyphs[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
    {'+', {0, 2, 7, 2, 0}}, {'e', {0, 7, 7, 4, 7}}, {'x', {0, 5, 2, 5, 0}},
};

const Glyph* glyph(char c) {
  for (const Glyph& g : kGlyphs)
    if (g.c == c) return &g;
  return nullptr;
}

void draw_digits(OIIO::ImageBuf& img, int x, int y, std::string_view text, int size,
                 const std::array<float, 3>& colour, TextAlign align) {
  const int px = std::max(1, size / 7);  // one glyph pixel, in image pixels
  const int advance = 4 * px;
  int width = 0;
  for (char c : text)
    if (glyph(c)) width += advance;
  if (align == TextAlign::Center) x -= width / 2;
  if (align == TextAlign::Right) x -= width;
  const int top = y - 5 * px;
  for (char c : text) {
    const Glyph* g = glyph(c);
    if (!g) continue;
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (g->rows[size_t(row)] & (4 >> col))
          OIIO::ImageBufAlgo::render_box(img, x + col * px, top + row * px, x + col * px + px - 1,
                                         top + row * px + px - 1, colour, true);
    x += advance;
  }
}

}  // namespace

PlotFont::PlotFont() {
  std::error_code ec;
  for (const char* f : kFontFiles)
    if (std::filesystem::is_regular_file(f, ec)) {
      font_ = f;
      break;
    }
}

PlotFont PlotFont::digits_only() {
  PlotFont f;
  f.font_.clear();
  return f;
}

void PlotFont::draw(OIIO::ImageBuf& img, int x, int y, const std::string& text, int size,
                    const std::array<float, 3>& colour, TextAlign align) const {
  if (font_.empty()) return draw_digits(img, x, y, text, size, colour, align);
  const OIIO::ROI box = OIIO::ImageBufAlgo::text_size(text, size, font_);
  const int tx = box.defined() ? box.width() : 0;
  const int left = align == TextAlign::Left ? x : align == TextAlign::Center ? x - tx / 2 : x - tx;
  if (!OIIO::ImageBufAlgo::render_text(img, left, y, text, size, font_, colour))
    draw_digits(img, x, y, text, size, colour, align);
}

}  // namespace vesper::measure
