#pragma once
// Statistics over renders for Z/t-tests: an image is rendered in independent
// batches (different seeds), and each tile's mean luminance gets a mean and a
// standard error from the spread between batches.
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/render/render.h"
#include "renderer/scene/scene.h"

namespace vesper::test {

struct TileStats {
  int tiles_x = 0, tiles_y = 0, batches = 0;
  std::vector<double> mean, se;  // per tile, luminance
};

// The luminance of the RGB channels starting at channel `c` (0: the beauty).
inline double pixel_luminance(const LayeredImage& img, int x, int y, size_t c = 0) {
  return 0.2126 * img.at(x, y, c) + 0.7152 * img.at(x, y, c + 1) + 0.0722 * img.at(x, y, c + 2);
}

// `options`: the estimator to render with (its spp and seed are set here;
// spp unset: the scene's). `aov`: the RGB AOV or layer to measure instead of
// the beauty (its name without .R).
inline TileStats tile_stats(const Scene& scene, int batches, std::optional<int> spp, int tile,
                            uint64_t seed0 = 1000, RenderOptions options = {},
                            const std::string& aov = "") {
  const int w = scene.film.width, h = scene.film.height;
  TileStats st;
  st.tiles_x = (w + tile - 1) / tile;
  st.tiles_y = (h + tile - 1) / tile;
  st.batches = batches;
  const size_t n = size_t(st.tiles_x * st.tiles_y);
  std::vector<std::vector<double>> per_batch(n);
  for (int b = 0; b < batches; ++b) {
    options.spp = spp;
    options.seed = seed0 + uint64_t(b);
    const RenderResult r = render(scene, options);
    const int c = aov.empty() ? 0 : r.image.channel_index(aov + ".R");
    if (c < 0) throw std::invalid_argument("tile_stats: no channel " + aov + ".R");
    std::vector<double> sum(n, 0.0), count(n, 0.0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t t = size_t((y / tile) * st.tiles_x + x / tile);
        sum[t] += pixel_luminance(r.image, x, y, size_t(c));
        count[t] += 1;
      }
    for (size_t t = 0; t < n; ++t) per_batch[t].push_back(sum[t] / count[t]);
  }
  for (size_t t = 0; t < n; ++t) {
    double m = 0;
    for (double v : per_batch[t]) m += v;
    m /= batches;
    double var = 0;
    for (double v : per_batch[t]) var += (v - m) * (v - m);
    var /= (batches - 1);
    st.mean.push_back(m);
    st.se.push_back(std::sqrt(var / batches));
  }
  return st;
}

// Two-sided critical value of Student's t for `tests` simultaneous tests at
// family-wise level alpha (Sidak correction).
inline double sidak_t_critical(double alpha, int tests, double dof) {
  const double per_test = 1.0 - std::pow(1.0 - alpha, 1.0 / tests);
  boost::math::students_t dist(dof);
  return boost::math::quantile(boost::math::complement(dist, per_test / 2));
}
inline double sidak_z_critical(double alpha, int tests) {
  const double per_test = 1.0 - std::pow(1.0 - alpha, 1.0 / tests);
  boost::math::normal dist;
  return boost::math::quantile(boost::math::complement(dist, per_test / 2));
}

}  // namespace vesper::test
