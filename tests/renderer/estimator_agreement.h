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

// Estimator a renders scene_a, b scene_b: the same scene built two ways
// (e.g. another render.light_selection). `aov`: compare that RGB AOV or
// layer instead of the beauty.
inline EstimatorNoise expect_estimators_agree(const Scene& scene_a, const RenderOptions& a,
                                              const Scene& scene_b, const RenderOptions& b,
                                              int batches = 10, int tile = 6,
                                              const std::string& aov = "") {
  const TileStats sa = tile_stats(scene_a, batches, a.spp, tile, 100, a, aov);
  const TileStats sb = tile_stats(scene_b, batches, b.spp, tile, 500, b, aov);
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

inline EstimatorNoise expect_estimators_agree(const Scene& scene, const RenderOptions& a,
                                              const RenderOptions& b, int batches = 10,
                                              int tile = 6) {
  return expect_estimators_agree(scene, a, scene, b, batches, tile);
}

}  // namespace vesper::test
