#pragma once
// Two estimators of the same image, tile by tile: both must render the same
// expected image (Welch t-test, alpha 0.01, Sidak over the tiles); the tiles'
// standard errors say which is less noisy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render_stats.h"

namespace vesper::test {

struct EstimatorNoise {
  double se_a = 0, se_b = 0;  // mean tile standard error of each estimator
  double median_ratio = 0;    // median over tiles of se_a / se_b (robust to one firefly)
};

// Each tile's mean luminance over `batches` renders with `options` (seeds
// seed0, seed0 + 1, ...).
inline TileStats tile_stats_with(const Scene& scene, RenderOptions options, uint64_t seed0,
                                 int batches, int tile) {
  TileStats st;
  const int w = scene.film.width, h = scene.film.height;
  st.tiles_x = w / tile;
  st.tiles_y = h / tile;
  st.batches = batches;
  std::vector<std::vector<double>> per(size_t(st.tiles_x * st.tiles_y));
  for (int b = 0; b < batches; ++b) {
    options.seed = seed0 + uint64_t(b);
    const RenderResult r = render(scene, options);
    std::vector<double> sum(per.size(), 0.0);
    for (int y = 0; y < st.tiles_y * tile; ++y)
      for (int x = 0; x < st.tiles_x * tile; ++x)
        sum[size_t((y / tile) * st.tiles_x + x / tile)] += pixel_luminance(r.image, x, y);
    for (size_t t = 0; t < per.size(); ++t) per[t].push_back(sum[t] / (tile * tile));
  }
  for (auto& v : per) {
    double m = 0, var = 0;
    for (double x : v) m += x;
    m /= batches;
    for (double x : v) var += (x - m) * (x - m);
    st.mean.push_back(m);
    st.se.push_back(std::sqrt(var / (batches - 1) / batches));
  }
  return st;
}

inline EstimatorNoise expect_estimators_agree(const Scene& scene, const RenderOptions& a,
                                              const RenderOptions& b, int batches = 10,
                                              int tile = 6) {
  const TileStats sa = tile_stats_with(scene, a, 100, batches, tile);
  const TileStats sb = tile_stats_with(scene, b, 500, batches, tile);
  const double crit = sidak_t_critical(0.01, int(sa.mean.size()), batches - 1);
  EstimatorNoise noise;
  double z_max = 0;
  for (size_t t = 0; t < sa.mean.size(); ++t) {
    const double se = std::sqrt(sa.se[t] * sa.se[t] + sb.se[t] * sb.se[t]);
    z_max = std::max(z_max, std::abs(sa.mean[t] - sb.mean[t]) / std::max(se, 1e-9));
    EXPECT_LT(std::abs(sa.mean[t] - sb.mean[t]) / std::max(se, 1e-9), crit)
        << "tile " << t << ": " << sa.mean[t] << " vs " << sb.mean[t];
    noise.se_a += sa.se[t] / double(sa.se.size());
    noise.se_b += sb.se[t] / double(sb.se.size());
  }
  std::vector<double> ratios;
  for (size_t t = 0; t < sa.se.size(); ++t)
    if (sb.se[t] > 0.0) ratios.push_back(sa.se[t] / sb.se[t]);
  if (!ratios.empty()) {
    std::nth_element(ratios.begin(), ratios.begin() + std::ptrdiff_t(ratios.size() / 2),
                     ratios.end());
    noise.median_ratio = ratios[ratios.size() / 2];
  }
  std::printf(
      "mean tile standard error: %.5f against %.5f (median ratio %.3f); largest |t| %.2f "
      "(critical %.2f)\n",
      noise.se_a, noise.se_b, noise.median_ratio, z_max, crit);
  return noise;
}

}  // namespace vesper::test
