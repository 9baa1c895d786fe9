#pragma once
// Per-tile tests of "the new render's mean equals the golden's": a tile's
// mean luminance in both, the variance of their difference from the
// variance channels, and a t statistic (docs/regression.md, "Statistics").
// Tiles find local changes; blocks of 2x2, 4x4, ... tiles up to the whole
// frame find faint changes spread over a large area (a fog density, a light's
// intensity), which no single tile has the samples to show.
#include <vector>

#include "regress/layer_channels.h"

namespace vesper::regress {

// Each pixel's variance comes from 4 independent sample streams: 3 degrees
// of freedom (docs/sampling.md).
constexpr double kPixelVarianceDof = 3;

struct TileTest {
  int x = 0, y = 0, width = 0, height = 0;  // pixels
  int pixels = 0;                           // with finite values and variances in both
  double golden_mean = 0, new_mean = 0;     // mean luminance over those pixels
  double sd = 0;        // standard deviation of new_mean - golden_mean under "no change"
  double dof = 0;       // its degrees of freedom (Welch-Satterthwaite)
  double t = 0;         // (new_mean - golden_mean) / sd
  double p_value = 1;   // two-sided
  bool tested = false;  // false: no usable pixel
};

struct TileGrid {
  int tile_size = 0, tiles_x = 0, tiles_y = 0;
  std::vector<TileTest> tiles;   // row-major
  std::vector<TileTest> blocks;  // 2^k x 2^k tiles for k = 1, 2, ... up to one block, the frame
};

// Both planes must have the same size and variances. Pixels whose value or
// variance is not finite in either render are left out of both (NaN/Inf are
// counted by the layer checks instead).
//
// The tile mean averages n pixels that are independent (each pixel's samples
// are its own), so its variance is the sum of the pixels' variances / n^2.
// A small floor (1e-6 of the larger mean, at least 1e-9) stands for float
// rounding, so noiseless tiles (a visible light, the sky) are tested too but
// never flagged for differences in the last bits.
TileGrid tile_tests(const LumaPlane& golden, const LumaPlane& fresh, int tile_size);

// The smallest |relative change| of a tile's mean a test at two-sided level
// `p` would flag: critical value * sd / max(|golden mean|, 1e-3).
double detectable_relative_change(const TileTest& tile, double p);

// (new - golden) / max(|golden|, 1e-3): the floor keeps black tiles finite.
double relative_change(double golden, double fresh);

}  // namespace vesper::regress
