#pragma once
// Text on the bench plots. OpenImageIO's render_text draws with FreeType, but
// this OIIO build finds no default font ("Could not set default font face":
// Debian ships none of the fonts it looks for), so it is given DejaVu Sans by
// path (fonts-dejavu-core, scripts/setup). Without that file the plot still
// needs its tick values: a tiny hand-drawn 3x5 font of digits and the few
// signs numbers use ("0-9 . - + e x"); other text is then left out.
#include <array>
#include <string>

#include <OpenImageIO/imagebuf.h>

namespace vesper::measure {

enum class TextAlign { Left, Center, Right };

class PlotFont {
 public:
  PlotFont();                     // finds the TrueType font, once
  static PlotFont digits_only();  // the fallback alone (what a machine without the font gets)
  bool has_truetype() const { return !font_.empty(); }
  // Draws `text` with its baseline at y. Without TrueType, characters the
  // digit font lacks are skipped (numbers always draw).
  void draw(OIIO::ImageBuf& img, int x, int y, const std::string& text, int size,
            const std::array<float, 3>& colour, TextAlign align = TextAlign::Left) const;

 private:
  std::string font_;
};

}  // namespace vesper::measure
