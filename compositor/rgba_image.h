#pragma once
// A float RGBA image (interleaved), the compositor's working buffer.
// Scene-linear Rec.709 until a display transform has been applied.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace vesper {

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<float> pixels;  // (y * width + x) * 4 + c, c in R, G, B, A

  RgbaImage() = default;
  RgbaImage(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h) * 4, 0.f) {}
  float& at(int x, int y, int c) {
    return pixels[(size_t(y) * size_t(width) + size_t(x)) * 4 + size_t(c)];
  }
  float at(int x, int y, int c) const {
    return pixels[(size_t(y) * size_t(width) + size_t(x)) * 4 + size_t(c)];
  }
  size_t pixel_count() const { return size_t(width) * size_t(height); }
};

// Every compositor error: what() names the file / JSON path / layer / view
// and what was expected, e.g. "comp.json: /layers/1/layer: no layer
// 'lightray' in out/night.exr (layers: beauty, candles, fog, ...)".
class CompError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vesper
