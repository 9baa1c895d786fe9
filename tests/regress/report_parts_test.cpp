// The report's parts on their own: text escaping and numbers, tick values,
// the difference heat map, the significance map, the histogram overlay and
// the trend charts.
#include <gtest/gtest.h>

#include <cmath>

#include "regress/colour_ramp.h"
#include "regress/difference_maps.h"
#include "regress/histogram_chart.h"
#include "regress/html_text.h"
#include "regress/svg_plot.h"
#include "regress/trend_chart.h"
#include "tests/regress/report_test_util.h"

namespace vesper::test {
namespace {

using namespace vesper::regress;

RgbaImage grey_image(int w, int h, float v) {
  RgbaImage img(w, h);
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = (i % 4 == 3) ? 1.f : v;
  return img;
}

TEST(ReportText, EscapesEverythingMarkupCouldMisread) {
  EXPECT_EQ(html_escape("<a href=\"x\">&'</a>"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
  EXPECT_EQ(safe_file_name("fog/../x y"), "fog_.._x_y");
  EXPECT_EQ(safe_file_name(".."), "_..");
  EXPECT_EQ(safe_file_name(""), "_");
}

TEST(ReportText, FormatsPercentSecondsAndFigures) {
  EXPECT_EQ(format_percent(0.041, true), "+4.1 %");
  EXPECT_EQ(format_percent(-0.0052, true), "-0.52 %");
  EXPECT_EQ(format_percent(0.0052), "0.52 %");
  EXPECT_EQ(format_percent(std::nan("")), "n/a");
  EXPECT_EQ(format_seconds(0.842), "0.842 s");
  EXPECT_EQ(format_seconds(12.34), "12.3 s");
  EXPECT_EQ(format_seconds(245), "4 min 05 s");
  EXPECT_EQ(format_seconds(-1), "n/a");
  EXPECT_EQ(format_figure(1234.6), "1235");
  EXPECT_EQ(format_figure(1.2), "1.2");
  EXPECT_EQ(format_figure(0.012345), "0.0123");
  EXPECT_EQ(format_figure(0), "0");
}

TEST(ReportPlot, NiceTicksCoverTheRangeInRoundSteps) {
  const std::vector<double> fifths = nice_ticks(0, 1, 5);
  ASSERT_EQ(fifths.size(), 6u);
  for (size_t i = 0; i < fifths.size(); ++i) EXPECT_NEAR(fifths[i], 0.2 * double(i), 1e-12);
  EXPECT_EQ(tick_label(fifths[3], 0.2), "0.6");
  EXPECT_EQ(tick_label(-1.75, 0.25), "-1.75");
  EXPECT_EQ(tick_label(-2, 0.25), "-2");
  EXPECT_EQ(tick_label(-0.0, 1), "0");
  const std::vector<double> t = nice_ticks(0, 1.37, 4);
  EXPECT_EQ(t.front(), 0);
  EXPECT_GE(t.back(), 1.37);
  EXPECT_NEAR(t[1] - t[0], 0.5, 1e-12);
  const std::vector<double> s = nice_ticks(-9.3, 2.1, 8);
  EXPECT_LE(s.front(), -9.3);
  EXPECT_GE(s.back(), 2.1);
  EXPECT_FALSE(nice_ticks(3, 3).empty());
}

TEST(ReportPictures, HeatMapOfIdenticalImagesIsTheBottomOfTheRamp) {
  const RgbaImage a = grey_image(8, 4, 0.5f);
  const HeatMap map = difference_heat_map(a, a);
  EXPECT_EQ(map.nonfinite, 0u);
  const auto bottom = ramp_colour(viridis_stops(), 0);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(map.image.at(x, y, c), bottom[size_t(c)]);
}

TEST(ReportPictures, HeatMapScalesToThe99thPercentileAndMarksNaNInMagenta) {
  RgbaImage golden = grey_image(20, 10, 0.5f), fresh = golden;
  for (int x = 0; x < 20; ++x)  // one row brighter by 0.1 (luminance of grey = its value)
    for (int c = 0; c < 3; ++c) fresh.at(x, 3, c) = 0.6f;
  for (int c = 0; c < 3; ++c) fresh.at(7, 7, c) = 100.f;  // a firefly must not set the scale
  fresh.at(2, 2, 1) = std::nanf("");
  const HeatMap map = difference_heat_map(golden, fresh);
  EXPECT_NEAR(map.top, 0.1, 1e-5);
  EXPECT_EQ(map.nonfinite, 1u);
  EXPECT_FLOAT_EQ(map.image.at(2, 2, 0), 1.f);
  EXPECT_FLOAT_EQ(map.image.at(2, 2, 1), 0.f);
  EXPECT_FLOAT_EQ(map.image.at(2, 2, 2), 1.f);
  const auto top = ramp_colour(viridis_stops(), 1);
  EXPECT_FLOAT_EQ(map.image.at(5, 3, 1), top[1]);
  EXPECT_FLOAT_EQ(map.image.at(7, 7, 1), top[1]);
  EXPECT_THROW(difference_heat_map(golden, grey_image(4, 4, 0.f)), std::invalid_argument);
}

LayerResult grid_layer() {
  LayerResult layer;
  layer.tile_size = 4;
  layer.tiles_x = 3;  // a 10 x 6 image: edge tiles 2 px
  layer.tiles_y = 2;
  layer.tile_z = {6.f, -7.f, 1.f, 0.f, 2.5f, -3.f};
  return layer;
}

TEST(ReportPictures, SignificanceMapColoursOnlyTheTilesThatCount) {
  LayerResult layer = grid_layer();
  layer.tile_significant = {1, 1, 0, 0, 0, 0};
  const SignificanceMap map = significance_map(layer, grey_image(10, 6, 0.5f));
  EXPECT_DOUBLE_EQ(map.z_scale, 7.0);
  const auto px = [&](int x, int y, int c) { return map.image.at(x, y, c); };
  EXPECT_GT(px(1, 1, 0), px(1, 1, 2) + 0.3f) << "brighter tile is red";
  EXPECT_GT(px(5, 1, 2), px(5, 1, 0) + 0.3f) << "darker tile is blue";
  for (auto [x, y] : {std::pair{9, 1}, std::pair{1, 5}, std::pair{9, 5}}) {
    EXPECT_FLOAT_EQ(px(x, y, 0), px(x, y, 1)) << "not significant: grey";
    EXPECT_FLOAT_EQ(px(x, y, 1), px(x, y, 2));
  }
  layer.tiles_x = 2;
  layer.tile_z.resize(4);
  EXPECT_THROW(significance_map(layer, grey_image(10, 6, 0.5f)), std::invalid_argument);
}

TEST(ReportPictures, WithoutAMaskTheLargestZTilesCount) {
  LayerResult layer = grid_layer();
  layer.significant_tiles = 3;
  EXPECT_EQ(significant_tile_mask(layer), (std::vector<uint8_t>{1, 1, 0, 0, 0, 1}));
  layer.significant_tiles = 0;
  EXPECT_EQ(significant_tile_mask(layer), (std::vector<uint8_t>(6, 0)));
  layer.tile_z.pop_back();
  EXPECT_TRUE(significant_tile_mask(layer).empty()) << "no usable grid";
}

TEST(ReportCharts, HistogramOverlayCropsToTheOccupiedStops) {
  RgbaImage a = grey_image(16, 16, 0.25f), b = grey_image(16, 16, 0.5f);  // -2 and -1 stops
  const Histogram ha = log2_histogram(a, LumaWeights::Rec709),
                  hb = log2_histogram(b, LumaWeights::Rec709);
  const std::string svg = histogram_overlay_svg(ha, hb, "h1", "Luminosity", wasserstein1(ha, hb));
  EXPECT_EQ(svg.rfind("<svg class=\"chart\"", 0), 0u);
  EXPECT_EQ(count_of(svg, "class=\"h-golden\" d="), 1u);
  EXPECT_EQ(count_of(svg, "class=\"h-new\" d="), 1u);
  EXPECT_NE(svg.find("Wasserstein-1 distance " + format_figure(wasserstein1(ha, hb), 3) + " stops"),
            std::string::npos)
      << svg.substr(0, 400);
  EXPECT_NE(svg.find(">-2</text>"), std::string::npos);
  EXPECT_EQ(svg.find(">-10</text>"), std::string::npos) << "empty stops are cut away";
}

std::vector<TrendPoint> trend_of(std::initializer_list<std::pair<double, Verdict>> runs) {
  std::vector<TrendPoint> points;
  int day = 1;
  for (auto [seconds, verdict] : runs) {
    TrendPoint& p = points.emplace_back();
    p.scene = "s";
    p.started_at = "2024-05-0" + std::to_string(day++) + "T02:00:00Z";
    p.render_seconds = seconds;
    p.reused = seconds == 0;
    p.verdict = verdict;
  }
  return points;
}

TEST(ReportCharts, TrendChartMarksEveryRunByVerdictShapeAndGapsReusedRuns) {
  const auto points = trend_of({{1.0, Verdict::Pass},
                                {1.1, Verdict::Pass},
                                {0, Verdict::Pass},
                                {1.4, Verdict::Regressed},
                                {1.2, Verdict::Error}});
  const std::string svg = trend_chart_svg(points, TrendFigure::RenderSeconds, "t", 1.0);
  EXPECT_EQ(count_of(svg, "<circle class=\"m-pass\""), 3u + 1) << "3 runs and the legend";
  EXPECT_EQ(count_of(svg, "class=\"m-regressed\""), 1u + 1);
  EXPECT_EQ(count_of(svg, "class=\"m-error\""), 1u + 1);
  EXPECT_EQ(count_of(svg, "<path class=\"line\""), 2u) << "the reused run breaks the line";
  EXPECT_NE(svg.find("2024-05-03T02:00:00Z: no value, pass, reused: not re-rendered"),
            std::string::npos);
  EXPECT_NE(svg.find("class=\"reference\" x1="), std::string::npos);
  EXPECT_NE(svg.find(">05-01 02:00</text>"), std::string::npos);
  EXPECT_NE(
      svg.find("<desc id=\"t-d\">Render time over 5 runs; latest 2024-05-05T02:00:00Z: 1.2 s"),
      std::string::npos);
}

TEST(ReportCharts, SceneTrendMergesSortsAndLimits) {
  std::vector<TrendPoint> history = trend_of({{1.0, Verdict::Pass}, {1.1, Verdict::Pass}});
  std::swap(history[0], history[1]);
  TrendPoint other = history[0];
  other.scene = "other";
  history.push_back(other);
  RunResult run;
  run.started_at = "2024-05-09T02:00:00Z";
  run.scenes.emplace_back().name = "s";
  auto points = scene_trend(&history, run, "s");
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0].started_at, "2024-05-01T02:00:00Z");
  EXPECT_EQ(points[2].started_at, run.started_at);
  history.push_back(points[2]);  // the history already holds this run: not twice
  EXPECT_EQ(scene_trend(&history, run, "s").size(), 3u);
  EXPECT_EQ(scene_trend(&history, run, "s", 2).front().started_at, "2024-05-02T02:00:00Z");
  EXPECT_EQ(scene_trend(nullptr, run, "s").size(), 1u);
}

}  // namespace
}  // namespace vesper::test
