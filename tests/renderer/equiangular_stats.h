#pragma once
// Equiangular sampling on against off, tile by tile: both must render the
// same expected image (t-test); the standard errors say which is less noisy.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "render_stats.h"

namespace vesper::test {

struct OnOffNoise {
  double se_on = 0, se_off = 0;  // mean tile standard error, equiangular on / off
};

// Each tile's mean luminance over `batches` renders (seeds seed0, seed0 + 1, ...).
inline TileStats equiangular_tile_stats(const Scene& scene, bool equiangular, uint64_t seed0,
                                        int batches, int tile) {
  TileStats st;
  const int w = scene.film.width, h = scene.film.height;
  st.tiles_x = w / tile;
  st.tiles_y = h / tile;
  st.batches = batches;
  std::vector<std::vector<double>> per(size_t(st.tiles_x * st.tiles_y));
  for (int b = 0; b < batches; ++b) {
    RenderOptions o;
    o.seed = seed0 + uint64_t(b);
    o.equiangular = equiangular;
    const RenderResult r = render(scene, o);
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

// Renders the scene with equiangular sampling on and off in batches; the
// tiles' means must agree (t-test, alpha 0.01, Sidak over the tiles).
inline OnOffNoise expect_on_and_off_agree(const Scene& scene, int batches = 10, int tile = 6) {
  const TileStats on = equiangular_tile_stats(scene, true, 100, batches, tile);
  const TileStats off = equiangular_tile_stats(scene, false, 500, batches, tile);
  const double crit = sidak_t_critical(0.01, int(on.mean.size()), batches - 1);
  OnOffNoise noise;
  for (size_t t = 0; t < on.mean.size(); ++t) {
    const double se = std::sqrt(on.se[t] * on.se[t] + off.se[t] * off.se[t]);
    EXPECT_LT(std::abs(on.mean[t] - off.mean[t]) / std::max(se, 1e-9), crit)
        << "tile " << t << ": " << on.mean[t] << " vs " << off.mean[t];
    noise.se_on += on.se[t] / double(on.se.size());
    noise.se_off += off.se[t] / double(off.se.size());
  }
  std::printf("mean tile standard error: equiangular on %.5f, off %.5f\n", noise.se_on,
              noise.se_off);
  return noise;
}

}  // namespace vesper::test
