#include "measure/noise_floor.h"

#include <stdexcept>

#include "measure/beauty.h"

namespace vesper::measure {
namespace {

void check_same_shape(const LayeredImage& a, const LayeredImage& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw std::invalid_argument("reference halves differ in size or channels");
}

}  // namespace

LayeredImage mean_of_halves(const LayeredImage& a, const LayeredImage& b) {
  check_same_shape(a, b);
  LayeredImage mean = a;
  for (size_t i = 0; i < mean.pixels.size(); ++i)
    mean.pixels[i] = float(0.5 * (double(a.pixels[i]) + double(b.pixels[i])));
  return mean;
}

double reference_noise_floor(const LayeredImage& a, const LayeredImage& b) {
  const LayeredImage ra = beauty_rgb(a), rb = beauty_rgb(b);
  check_same_shape(ra, rb);
  double sum = 0;
  for (size_t i = 0; i < ra.pixels.size(); ++i) {
    const double va = ra.pixels[i], vb = rb.pixels[i], r = 0.5 * (va + vb);
    sum += (va - vb) * (va - vb) / (r * r + 0.01);
  }
  return ra.pixels.empty() ? 0 : sum / double(ra.pixels.size()) / 4.0;
}

}  // namespace vesper::measure
