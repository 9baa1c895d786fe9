#include "regress/tile_statistics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "regress/student_t.h"

namespace vesper::regress {
namespace {

constexpr double kMeanFloor = 1e-3;      // luminance; keeps relative changes of black tiles finite
constexpr double kRoundingFloor = 1e-6;  // relative sd standing for float rounding

// Sums over a tile's usable pixels of both renders.
struct TileSums {
  int pixels = 0;
  double golden = 0, fresh = 0;
  double variance = 0;          // sum of both renders' pixel variances
  double variance_squares = 0;  // sum of their squares, for the degrees of freedom
};

bool usable(const LumaPlane& p, size_t i) {
  return std::isfinite(p.value[i]) && std::isfinite(p.variance[i]) && p.variance[i] >= 0;
}

TileSums sum_tile(const LumaPlane& g, const LumaPlane& n, int x0, int y0, int x1, int y1) {
  TileSums s;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t i = size_t(y) * size_t(g.width) + size_t(x);
      if (!usable(g, i) || !usable(n, i)) continue;
      ++s.pixels;
      s.golden += g.value[i];
      s.fresh += n.value[i];
      s.variance += g.variance[i] + n.variance[i];
      s.variance_squares += g.variance[i] * g.variance[i] + n.variance[i] * n.variance[i];
    }
  return s;
}

TileTest test_tile(const TileSums& s, TileTest tile) {
  tile.pixels = s.pixels;
  if (s.pixels == 0) return tile;
  const double n = s.pixels;
  tile.golden_mean = s.golden / n;
  tile.new_mean = s.fresh / n;
  const double floor_sd =
      kRoundingFloor * std::max({std::abs(tile.golden_mean), std::abs(tile.new_mean), kMeanFloor});
  const double noise = s.variance / (n * n);
  const double variance = noise + floor_sd * floor_sd;
  tile.sd = std::sqrt(variance);
  // Welch-Satterthwaite: each pixel variance has 3 degrees of freedom, the
  // floor is exact. Plugging the estimates into the squares overstates
  // them, so the degrees of freedom come out low: conservative.
  const double noise_squares = s.variance_squares / (n * n * n * n);
  tile.dof =
      noise_squares > 0 ? variance * variance / (noise_squares / kPixelVarianceDof) : kInfiniteDof;
  const double diff = tile.new_mean - tile.golden_mean;
  tile.t = diff / tile.sd;
  tile.p_value = two_sided_p_value(tile.t, tile.dof);
  tile.tested = true;
  return tile;
}

}  // namespace

TileGrid tile_tests(const LumaPlane& golden, const LumaPlane& fresh, int tile_size) {
  if (golden.width != fresh.width || golden.height != fresh.height || tile_size < 1 ||
      golden.variance.empty() || fresh.variance.empty())
    throw std::invalid_argument("tile_tests: planes of different sizes or without variance");
  TileGrid grid;
  grid.tile_size = tile_size;
  grid.tiles_x = (golden.width + tile_size - 1) / tile_size;
  grid.tiles_y = (golden.height + tile_size - 1) / tile_size;
  for (int ty = 0; ty < grid.tiles_y; ++ty)
    for (int tx = 0; tx < grid.tiles_x; ++tx) {
      TileTest tile;
      tile.x = tx * tile_size;
      tile.y = ty * tile_size;
      tile.width = std::min(tile_size, golden.width - tile.x);
      tile.height = std::min(tile_size, golden.height - tile.y);
      const TileSums sums =
          sum_tile(golden, fresh, tile.x, tile.y, tile.x + tile.width, tile.y + tile.height);
      grid.tiles.push_back(test_tile(sums, tile));
    }
  return grid;
}

double detectable_relative_change(const TileTest& tile, double p) {
  return two_sided_critical_value(p, tile.dof) * tile.sd /
         std::max(std::abs(tile.golden_mean), kMeanFloor);
}

double relative_change(double golden, double fresh) {
  return (fresh - golden) / std::max(std::abs(golden), kMeanFloor);
}

}  // namespace vesper::regress
