#pragma once
// A regression run to write reports about, from real renders of the small
// Cornell box with per-pixel variance: a golden, a re-render with another
// seed (passes), a re-render with the red wall 25 % brighter (regresses), a
// scene whose golden is missing (error) and one the farm reused, plus six
// earlier runs of history for the trend charts.
//
// The per-tile Z here is a plain Bonferroni test, enough to give the report
// realistic pictures; the comparison proper is regress/compare.h's.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "compositor/histogram.h"
#include "compositor/layer_mix.h"
#include "regress/regress_result.h"
#include "regress/trend.h"
#include "renderer/output/exr_io.h"
#include "renderer/render/frame.h"
#include "tests/renderer/scene_fixtures.h"

namespace vesper::test {

struct ReportFixture {
  regress::RunResult run;
  std::vector<regress::TrendPoint> history;  // earlier runs, oldest first
};

// 64 x 48 at 32 spp, beauty and variance.R/G/B; `red_gain` scales the red wall's albedo.
inline LayeredImage render_report_cornell(uint64_t seed, float red_gain) {
  SceneDescription d = small_cornell(64, 48, 32);
  d.materials[1] = DiffuseMaterialDesc{Rgb(0.63f * red_gain, 0.065f * red_gain, 0.05f * red_gain)};
  RenderOptions options;
  options.seed = seed;
  options.aovs = std::vector<Aov>{Aov::Variance};
  return render_frame(d, options).image;
}

struct TileStats {
  double mean = 0, variance = 0;  // of the tile's mean luminance
};

inline TileStats tile_stats(const LayeredImage& img, int x0, int y0, int x1, int y1) {
  const auto w = luma_coefficients(LumaWeights::Rec709);
  const char* names[6] = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
  int c[6];
  for (int i = 0; i < 6; ++i) c[i] = img.channel_index(names[i]);
  TileStats t;
  const double n = double(x1 - x0) * double(y1 - y0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (size_t k = 0; k < 3; ++k) {
        t.mean += w[k] * img.at(x, y, size_t(c[k])) / n;
        t.variance += w[k] * w[k] * img.at(x, y, size_t(c[k + 3])) / (n * n);
      }
  return t;
}

// Beauty compared tile by tile: signed Z, Bonferroni at alpha = 1e-4.
inline regress::LayerResult crude_beauty_result(const LayeredImage& golden,
                                                const LayeredImage& fresh, int tile = 8) {
  regress::LayerResult r;
  r.layer = "beauty";
  r.has_variance = true;
  r.tile_size = tile;
  r.tiles_x = (golden.width + tile - 1) / tile;
  r.tiles_y = (golden.height + tile - 1) / tile;
  r.tiles = r.tiles_x * r.tiles_y;
  const double z_crit = 4.5;  // about two-sided 1e-4 / 48 tiles
  std::vector<double> detectable;
  for (int ty = 0; ty < r.tiles_y; ++ty)
    for (int tx = 0; tx < r.tiles_x; ++tx) {
      const int x0 = tx * tile, y0 = ty * tile;
      const int x1 = std::min(golden.width, x0 + tile), y1 = std::min(golden.height, y0 + tile);
      const TileStats g = tile_stats(golden, x0, y0, x1, y1), n = tile_stats(fresh, x0, y0, x1, y1);
      const double sd = std::sqrt(g.variance + n.variance);
      const double z = sd > 0 ? (n.mean - g.mean) / sd : 0.0;
      const double base = std::max(std::fabs(g.mean), 1e-3);
      detectable.push_back(z_crit * sd / base);
      r.tile_z.push_back(float(z));
      const bool significant = std::fabs(z) > z_crit;
      r.tile_significant.push_back(significant ? 1 : 0);
      r.max_abs_z = std::max(r.max_abs_z, std::fabs(z));
      if (!significant) continue;
      ++r.significant_tiles;
      r.worst.push_back({x0, y0, x1 - x0, y1 - y0, z, std::erfc(std::fabs(z) / std::sqrt(2.0)),
                         g.mean, n.mean, (n.mean - g.mean) / base});
    }
  std::sort(r.worst.begin(), r.worst.end(), [](const regress::Region& a, const regress::Region& b) {
    return std::fabs(a.z) > std::fabs(b.z);
  });
  if (r.worst.size() > 3) r.worst.resize(3);
  std::nth_element(detectable.begin(), detectable.begin() + std::ptrdiff_t(detectable.size() / 2),
                   detectable.end());
  r.min_detectable_change = detectable[detectable.size() / 2];
  r.histogram_distance =
      wasserstein1(log2_histogram(extract_layer(golden, "beauty", "golden"), LumaWeights::Rec709),
                   log2_histogram(extract_layer(fresh, "beauty", "new"), LumaWeights::Rec709));
  if (r.significant_tiles > 0) {
    r.verdict = regress::Verdict::Regressed;
    r.reasons.push_back(fmt::format("{} tiles changed beyond noise (max |Z| {:.1f})",
                                    r.significant_tiles, r.max_abs_z));
  }
  return r;
}

inline regress::SceneResult fixture_scene(const std::string& name,
                                          const std::filesystem::path& golden,
                                          const std::filesystem::path& fresh, double golden_s,
                                          double new_s) {
  regress::SceneResult s;
  s.name = name;
  s.golden_image = golden.string();
  s.new_image = fresh.string();
  s.golden_seconds = golden_s;
  s.new_seconds = new_s;
  s.new_seconds_repeats = {new_s * 0.98, new_s, new_s * 1.03};
  return s;
}

// Renders into `dir` (golden.exr, same.exr, brighter.exr) and builds the run.
inline ReportFixture make_report_fixture(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const LayeredImage golden = render_report_cornell(1, 1.f);
  const LayeredImage same = render_report_cornell(2, 1.f);
  const LayeredImage brighter = render_report_cornell(3, 1.25f);
  write_exr(golden, dir / "golden.exr");
  write_exr(same, dir / "same.exr");
  write_exr(brighter, dir / "brighter.exr");

  ReportFixture f;
  f.run.suite = (dir / "suite.json").string();
  f.run.started_at = "2024-05-07T02:00:00Z";
  f.run.renderer_version = "vesper 0.13.0 (test)";
  f.run.verdict = regress::Verdict::Error;

  regress::SceneResult pass =
      fixture_scene("cornell", dir / "golden.exr", dir / "same.exr", 1.2, 1.22);
  pass.layers.push_back(crude_beauty_result(golden, same));
  regress::SceneResult wall =
      fixture_scene("cornell-red-wall", dir / "golden.exr", dir / "brighter.exr", 1.2, 1.25);
  wall.layers.push_back(crude_beauty_result(golden, brighter));
  wall.verdict = wall.layers[0].verdict;
  regress::SceneResult missing =
      fixture_scene("missing-golden", dir / "goldens/missing-golden.exr", dir / "same.exr", 0, 1.2);
  missing.verdict = regress::Verdict::Error;
  missing.reasons.push_back("no golden: " + (dir / "goldens/missing-golden.exr").string() +
                            " does not exist (write it with --update-goldens)");
  regress::SceneResult reused = pass;
  reused.name = "cornell-reused";
  reused.reused = true;
  reused.new_seconds_repeats.clear();
  f.run.scenes = {pass, wall, missing, reused};

  for (int day = 1; day <= 6; ++day)
    for (const regress::SceneResult& s : f.run.scenes) {
      regress::TrendPoint p = regress::trend_point(s, fmt::format("2024-05-0{}T02:00:00Z", day));
      p.verdict = (s.name == "cornell-red-wall" && day == 3) ? regress::Verdict::Error
                                                             : regress::Verdict::Pass;
      p.render_seconds = 1.1 + 0.02 * day;
      p.max_abs_z = 1.5 + 0.3 * std::sin(day);
      f.history.push_back(p);
    }
  return f;
}

}  // namespace vesper::test
