#include "regress/compare_layer.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "regress/holm.h"
#include "regress/layer_checks.h"
#include "regress/median.h"
#include "regress/tile_statistics.h"

namespace vesper::regress {
namespace {

constexpr size_t kMaxRegions = 20;

Region region_of(const TileTest& t) {
  return {t.x,           t.y,        t.width,
          t.height,      t.t,        t.p_value,
          t.golden_mean, t.new_mean, relative_change(t.golden_mean, t.new_mean)};
}

std::string where(const Region& r) {
  return fmt::format("x {}-{} y {}-{}", r.x, r.x + r.width - 1, r.y, r.y + r.height - 1);
}

std::string count_regions(int tiles, int blocks) {
  std::string s;
  if (tiles > 0) s = fmt::format("{} tile{}", tiles, tiles == 1 ? "" : "s");
  if (blocks > 0)
    s += fmt::format("{}{} larger block{}", s.empty() ? "" : " and ", blocks,
                     blocks == 1 ? "" : "s");
  return s;
}

// "brighter in 3 tiles and 1 larger block, worst +4.1 % at x 32-47 y 16-31 (Z 7.2)".
void describe_regions(const std::vector<Region>& regions, int tile_size, LayerResult& out) {
  for (int sign : {+1, -1}) {
    int tiles = 0, blocks = 0;
    const Region* worst = nullptr;
    for (const Region& r : regions) {
      if ((r.z > 0) != (sign > 0)) continue;
      ++(r.width <= tile_size && r.height <= tile_size ? tiles : blocks);
      if (!worst || std::abs(r.relative_change) > std::abs(worst->relative_change)) worst = &r;
    }
    if (!worst) continue;
    out.reasons.push_back(fmt::format(
        "{} in {}, worst {:+.2f} % at {} (Z {:.1f})", sign > 0 ? "brighter" : "darker",
        count_regions(tiles, blocks), 100 * worst->relative_change, where(*worst), worst->z));
  }
}

// The tiles' figures for the significance map and the summary.
std::vector<const TileTest*> tested_tiles(const TileGrid& grid, LayerResult& out) {
  out.tile_size = grid.tile_size;
  out.tiles_x = grid.tiles_x;
  out.tiles_y = grid.tiles_y;
  out.tile_z.assign(grid.tiles.size(), 0.f);
  out.tile_significant.assign(grid.tiles.size(), 0);
  std::vector<const TileTest*> tested;
  for (size_t i = 0; i < grid.tiles.size(); ++i) {
    const TileTest& t = grid.tiles[i];
    if (!t.tested) continue;
    tested.push_back(&t);
    out.tile_z[i] = float(t.t);
  }
  out.tiles = int(tested.size());
  return tested;
}

// Holm over every tested tile and block (one family); significant ones
// changed by at least min_relative_change become regions, the most
// significant first.
void judge_tiles(const TileGrid& grid, const Thresholds& th, LayerResult& out) {
  const std::vector<const TileTest*> tiles = tested_tiles(grid, out);
  std::vector<const TileTest*> family = tiles;
  for (const TileTest& b : grid.blocks)
    if (b.tested) family.push_back(&b);
  if (family.empty()) return;
  std::vector<double> p;
  for (const TileTest* t : family) {
    p.push_back(t->p_value);
    out.max_abs_z = std::max(out.max_abs_z, std::abs(t->t));
  }
  const std::vector<bool> rejected = holm_rejections(p, th.alpha);
  // The first Holm step is the hardest: alpha / m (two-sided).
  const double first_step = th.alpha / double(family.size());
  std::vector<double> detectable;
  for (const TileTest* t : tiles) detectable.push_back(detectable_relative_change(*t, first_step));
  out.min_detectable_change = median(std::move(detectable));
  out.frame_detectable_change = detectable_relative_change(*family.back(), first_step);
  std::vector<Region> regions;
  int small = 0;
  for (size_t i = 0; i < family.size(); ++i) {
    if (!rejected[i]) continue;
    out.significant_tiles += i < tiles.size();
    const Region r = region_of(*family[i]);
    if (std::abs(r.relative_change) < th.min_relative_change) {
      ++small;
      continue;
    }
    regions.push_back(r);
    if (i < tiles.size()) out.tile_significant[size_t(tiles[i] - grid.tiles.data())] = 1;
  }
  std::sort(regions.begin(), regions.end(),
            [](const Region& a, const Region& b) { return std::abs(a.z) > std::abs(b.z); });
  describe_regions(regions, grid.tile_size, out);
  if (!regions.empty()) out.verdict = Verdict::Regressed;
  if (small > 0)
    out.reasons.push_back(
        fmt::format("{} region(s) differ beyond noise but by less than "
                    "min_relative_change {:g} %: ignored",
                    small, 100 * th.min_relative_change));
  if (regions.size() > kMaxRegions) regions.resize(kMaxRegions);
  out.worst = std::move(regions);
}

void judge_nonfinite(const NonfiniteCount& n, LayerResult& out) {
  out.golden_nonfinite = n.golden;
  out.new_nonfinite = n.fresh;
  out.introduced_nonfinite = n.introduced;
  out.introduced_nonfinite_at = n.introduced_at;
  if (n.introduced == 0) return;
  out.verdict = Verdict::Regressed;
  out.reasons.push_back(fmt::format("{} new NaN/Inf pixel{} (golden {}, new {}), first at ({}, {})",
                                    n.introduced, n.introduced == 1 ? "" : "s", n.golden, n.fresh,
                                    n.introduced_at[0].x, n.introduced_at[0].y));
}

// Regressed only when the distance is beyond both the threshold and what
// noise alone gives (layer_checks.h).
void judge_histogram(const LumaPlane& g, const LumaPlane& f, const Thresholds& th,
                     LayerResult& out) {
  if (g.value.empty()) return;
  const HistogramDistance d = histogram_distance(g, f);
  out.histogram_distance = d.distance;
  out.histogram_noise = d.noise_level;
  if (d.distance <= th.max_histogram_distance) return;
  if (d.distance <= d.noise_level) {
    out.reasons.push_back(fmt::format(
        "luminosity histogram moved {:.3f} stops, beyond max_histogram_distance {:g} but within "
        "what noise alone moves it ({:.3f}): not counted",
        d.distance, th.max_histogram_distance, d.noise_level));
    return;
  }
  out.verdict = Verdict::Regressed;
  out.reasons.push_back(fmt::format(
      "luminosity histogram moved {:.3f} stops (Wasserstein-1; limit max_histogram_distance {:g}, "
      "noise alone {:.3f})",
      d.distance, th.max_histogram_distance, d.noise_level));
}

// What a layer without a tile test was checked for.
std::string untested_reason(const LayerChannels& layer, bool has_value) {
  if (!has_value)
    return "neither RGB nor a single channel: NaN/Inf checked only (no tile test, no histogram)";
  const std::string v = layer.name == kBeautyLayer ? "variance" : layer.name + ".variance";
  return "no variance channels (" + v +
         ".R/G/B) in both renders: NaN/Inf and histogram checked, no per-tile test";
}

}  // namespace

LayerResult compare_layer(const LayeredImage& golden, const LayerChannels& golden_layer,
                          const LayeredImage& fresh, const LayerChannels& new_layer,
                          const Thresholds& thresholds) {
  LayerResult out;
  out.layer = golden_layer.name;
  judge_nonfinite(count_nonfinite(golden, golden_layer, fresh, new_layer), out);
  const auto g = layer_luminance(golden, golden_layer);
  const auto f = layer_luminance(fresh, new_layer);
  if (!g || !f) {
    out.reasons.push_back(untested_reason(golden_layer, false));
    return out;
  }
  judge_histogram(*g, *f, thresholds, out);
  out.has_variance = !g->variance.empty() && !f->variance.empty();
  if (!out.has_variance) {
    out.reasons.push_back(untested_reason(golden_layer, true));
    return out;
  }
  judge_tiles(tile_tests(*g, *f, thresholds.tile_size), thresholds, out);
  if (out.verdict == Verdict::Pass)
    out.reasons.push_back(fmt::format(
        "no change beyond noise in {} tiles (max |Z| {:.2f}); would show a change of {:.2f} % in "
        "a tile, {:.2f} % over the frame",
        out.tiles, out.max_abs_z, 100 * out.min_detectable_change,
        100 * out.frame_detectable_change));
  return out;
}

}  // namespace vesper::regress
