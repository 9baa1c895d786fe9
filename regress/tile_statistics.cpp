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

TileSums& operator+=(TileSums& a, const TileSums& b) {
  a.pixels += b.pixels;
  a.golden += b.golden;
  a.fresh += b.fresh;
  a.variance += b.variance;
  a.variance_squares += b.variance_squares;
  return a;
}

TileSums sum_tile(const LumaPlane& g, const LumaPlane& n, int x0, int y0, int x1, int y1) {
  TileSums s;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t i = size_t(y) * size_t(g.width) + size_t(x);
      if (!usable(g, i) || !usable(n, i)) continue;
      TileSums p{1, g.value[i], n.value[i], g.variance[i] + n.variance[i],
                 g.variance[i] * g.variance[i] + n.variance[i] * n.variance[i]};
      s += p;
    }
  return s;
}

// One level of the pyramid: `sums` over nx x ny cells of `cell` pixels.
struct Level {
  int cell = 0, nx = 0, ny = 0;
  std::vector<TileSums> sums;
  std::vector<int> parts;  // cells of the finer level merged into each (empty: the tiles)
};

// Merges 2x2 cells of `fine` (fewer at the right and bottom edges).
Level coarser(const Level& fine) {
  Level c{fine.cell * 2, (fine.nx + 1) / 2, (fine.ny + 1) / 2, {}, {}};
  c.sums.resize(size_t(c.nx) * size_t(c.ny));
  c.parts.resize(c.sums.size());
  for (int y = 0; y < fine.ny; ++y)
    for (int x = 0; x < fine.nx; ++x) {
      const size_t i = size_t(y / 2) * size_t(c.nx) + size_t(x / 2);
      c.sums[i] += fine.sums[size_t(y) * size_t(fine.nx) + size_t(x)];
      ++c.parts[i];
    }
  return c;
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

// The tests of one level's cells, clipped to the frame. A block made of a
// single finer cell (at the right or bottom edge) repeats that cell's test
// and is left out: it would only enlarge the family.
std::vector<TileTest> test_level(const Level& level, int width, int height) {
  std::vector<TileTest> tests;
  for (int ty = 0; ty < level.ny; ++ty)
    for (int tx = 0; tx < level.nx; ++tx) {
      if (!level.parts.empty() && level.parts[size_t(ty) * size_t(level.nx) + size_t(tx)] == 1)
        continue;
      TileTest tile;
      tile.x = tx * level.cell;
      tile.y = ty * level.cell;
      tile.width = std::min(level.cell, width - tile.x);
      tile.height = std::min(level.cell, height - tile.y);
      tests.push_back(test_tile(level.sums[size_t(ty) * size_t(level.nx) + size_t(tx)], tile));
    }
  return tests;
}

}  // namespace

TileGrid tile_tests(const LumaPlane& golden, const LumaPlane& fresh, int tile_size) {
  if (golden.width != fresh.width || golden.height != fresh.height || tile_size < 1 ||
      golden.variance.empty() || fresh.variance.empty())
    throw std::invalid_argument("tile_tests: planes of different sizes or without variance");
  Level level{tile_size,
              (golden.width + tile_size - 1) / tile_size,
              (golden.height + tile_size - 1) / tile_size,
              {},
              {}};
  for (int ty = 0; ty < level.ny; ++ty)
    for (int tx = 0; tx < level.nx; ++tx)
      level.sums.push_back(sum_tile(golden, fresh, tx * tile_size, ty * tile_size,
                                    std::min((tx + 1) * tile_size, golden.width),
                                    std::min((ty + 1) * tile_size, golden.height)));
  TileGrid grid{tile_size, level.nx, level.ny, test_level(level, golden.width, golden.height), {}};
  while (level.nx > 1 || level.ny > 1) {
    level = coarser(level);
    const std::vector<TileTest> blocks = test_level(level, golden.width, golden.height);
    grid.blocks.insert(grid.blocks.end(), blocks.begin(), blocks.end());
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
