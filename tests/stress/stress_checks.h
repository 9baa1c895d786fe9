#pragma once
// The checks every stress case makes on a render: no NaN/Inf anywhere, pixel
// means inside an analytic bound (allowing for each pixel's own noise), light
// where light is visible, and agreement with a twin render.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/renderer/render_stats.h"
#include "tests/renderer/scene_fixtures.h"

namespace vesper::test {

// Family-wise false-alarm rate of every statistical check in the stress suite.
inline constexpr double kStressAlpha = 0.01;

// Renders with the variance AOV (the checks below need it) and the geometric
// AOVs (normals of degenerate triangles must be finite too).
inline RenderResult render_with_variance(const Scene& scene, int spp, uint64_t seed = 11) {
  RenderOptions o;
  o.spp = spp;
  o.seed = seed;
  o.aovs = std::vector<Aov>{Aov::Variance, Aov::Albedo, Aov::Normal, Aov::Depth};
  return render(scene, o);
}

// Zero NaN/Inf: none caught in the integrator and none in any channel.
inline void expect_finite(const RenderResult& r, const std::string& what) {
  EXPECT_EQ(r.stats.nonfinite_samples, 0u) << what;
  size_t bad = 0;
  for (float v : r.image.pixels)
    if (!std::isfinite(v)) ++bad;
  EXPECT_EQ(bad, 0u) << what << ": non-finite pixel values";
}

// The expected radiance of a pixel is at most `bound`, derived by the caller:
// with emitters that do not reflect (quad, sphere, environment lights), the
// radiance a camera ray receives is at most the sum S of their largest
// radiances. By induction on the path length: a surface or medium point
// sends out at most its albedo (<= 1, energy conservation) times the most it
// receives, which is at most S. A pixel mean may exceed S by
// noise only: one-sided Z-test per pixel and channel with the pixel's own
// variance of the mean, Sidak over all of them at kStressAlpha. A tiny relative
// slack covers float rounding where a pixel has no noise at all.
inline void expect_below_bound(const RenderResult& r, double bound, const std::string& what) {
  const LayeredImage& img = r.image;
  const int w = img.width, h = img.height;
  const int var0 = img.channel_index("variance.R");
  ASSERT_GE(var0, 0) << "render with render_with_variance()";
  const double z = sidak_z_critical(2 * kStressAlpha, w * h * 3);  // one-sided
  int over = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = img.at(x, y, c), se = std::sqrt(std::max(0.f, img.at(x, y, var0 + c)));
        if (v > bound * (1 + 1e-5) + z * se) {
          if (over++ < 3)
            ADD_FAILURE() << what << ": pixel " << x << "," << y << " channel " << c << " = " << v
                          << " > bound " << bound << " + " << z << " * " << se;
        }
      }
  EXPECT_EQ(over, 0) << what;
}

// Mean of channel c over the image and its standard error from the variance AOV
// (pixels are independent estimates).
struct ImageMean {
  double mean = 0, se = 0;
};
inline ImageMean image_mean(const RenderResult& r, int c) {
  const LayeredImage& img = r.image;
  const int var0 = img.channel_index("variance.R");
  const double n = double(img.width) * img.height;
  double sum = 0, var = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      sum += img.at(x, y, c);
      if (var0 >= 0) var += img.at(x, y, var0 + c);
    }
  return {sum / n, std::sqrt(var) / n};
}

// Light is visible: the image's mean green is significantly above zero (Z-test).
inline void expect_lit(const RenderResult& r, const std::string& what) {
  const ImageMean m = image_mean(r, 1);
  EXPECT_GT(m.mean, 0.0) << what;
  EXPECT_GT(m.mean, sidak_z_critical(2 * kStressAlpha, 1) * m.se) << what << ": mean " << m.mean;
}

// Per-tile Welch t-test of two scenes' luminance over independent seed
// batches, Sidak over tiles at kStressAlpha: the two render the same image.
inline void expect_same_image(const Scene& a, const Scene& b, const std::string& what,
                              int batches = 10, int spp = 8, int tile = 8) {
  const TileStats sa = tile_stats(a, batches, spp, tile, 100);
  const TileStats sb = tile_stats(b, batches, spp, tile, 500);
  // Welch with equal batch counts: dof >= batches - 1; the smaller is conservative.
  const double crit = sidak_t_critical(kStressAlpha, int(sa.mean.size()), batches - 1);
  for (size_t t = 0; t < sa.mean.size(); ++t) {
    const double se = std::sqrt(sa.se[t] * sa.se[t] + sb.se[t] * sb.se[t]);
    const double scale = std::max(std::abs(sa.mean[t]), std::abs(sb.mean[t]));
    // Noise-free tiles (delta lights, sky): float rounding only.
    EXPECT_LT(std::abs(sa.mean[t] - sb.mean[t]) / std::max(se, 1e-6 * scale + 1e-30), crit)
        << what << ": tile " << t << ": " << sa.mean[t] << " vs " << sb.mean[t];
  }
}

}  // namespace vesper::test
