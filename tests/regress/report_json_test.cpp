// report.json keeps every field of a RunResult and reads back what it wrote;
// a damaged report is rejected with the JSON path of the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/json_error.h"
#include "regress/report_json.h"
#include "sample_results.h"

namespace vesper::regress {
namespace {

void expect_same(const LayerResult& a, const LayerResult& b) {
  EXPECT_EQ(a.layer, b.layer);
  EXPECT_EQ(a.verdict, b.verdict);
  EXPECT_EQ(a.reasons, b.reasons);
  ASSERT_EQ(a.worst.size(), b.worst.size());
  for (size_t i = 0; i < a.worst.size(); ++i) {
    EXPECT_EQ(a.worst[i].x, b.worst[i].x);
    EXPECT_EQ(a.worst[i].height, b.worst[i].height);
    EXPECT_EQ(a.worst[i].z, b.worst[i].z);
    EXPECT_EQ(a.worst[i].p_value, b.worst[i].p_value);
    EXPECT_EQ(a.worst[i].relative_change, b.worst[i].relative_change);
  }
  EXPECT_EQ(a.tiles, b.tiles);
  EXPECT_EQ(a.significant_tiles, b.significant_tiles);
  EXPECT_EQ(a.max_abs_z, b.max_abs_z);
  EXPECT_EQ(a.min_detectable_change, b.min_detectable_change);
  EXPECT_EQ(a.frame_detectable_change, b.frame_detectable_change);
  EXPECT_EQ(a.histogram_distance, b.histogram_distance);
  EXPECT_EQ(a.histogram_noise, b.histogram_noise);
  EXPECT_EQ(a.golden_nonfinite, b.golden_nonfinite);
  EXPECT_EQ(a.new_nonfinite, b.new_nonfinite);
  EXPECT_EQ(a.introduced_nonfinite, b.introduced_nonfinite);
  ASSERT_EQ(a.introduced_nonfinite_at.size(), b.introduced_nonfinite_at.size());
  for (size_t i = 0; i < a.introduced_nonfinite_at.size(); ++i) {
    EXPECT_EQ(a.introduced_nonfinite_at[i].x, b.introduced_nonfinite_at[i].x);
    EXPECT_EQ(a.introduced_nonfinite_at[i].y, b.introduced_nonfinite_at[i].y);
  }
  EXPECT_EQ(a.has_variance, b.has_variance);
  EXPECT_EQ(a.tile_size, b.tile_size);
  EXPECT_EQ(a.tiles_x, b.tiles_x);
  EXPECT_EQ(a.tiles_y, b.tiles_y);
  EXPECT_EQ(a.tile_z, b.tile_z);
}

void expect_same(const RunResult& a, const RunResult& b) {
  EXPECT_EQ(a.suite, b.suite);
  EXPECT_EQ(a.started_at, b.started_at);
  EXPECT_EQ(a.renderer_version, b.renderer_version);
  EXPECT_EQ(a.verdict, b.verdict);
  ASSERT_EQ(a.scenes.size(), b.scenes.size());
  for (size_t i = 0; i < a.scenes.size(); ++i) {
    const SceneResult &s = a.scenes[i], &t = b.scenes[i];
    EXPECT_EQ(s.name, t.name);
    EXPECT_EQ(s.verdict, t.verdict);
    EXPECT_EQ(s.reasons, t.reasons);
    EXPECT_EQ(s.channels_added, t.channels_added);
    EXPECT_EQ(s.channels_missing, t.channels_missing);
    EXPECT_EQ(s.golden_seconds, t.golden_seconds);
    EXPECT_EQ(s.new_seconds, t.new_seconds);
    EXPECT_EQ(s.new_seconds_repeats, t.new_seconds_repeats);
    EXPECT_EQ(s.reused, t.reused);
    EXPECT_EQ(s.golden_image, t.golden_image);
    EXPECT_EQ(s.new_image, t.new_image);
    ASSERT_EQ(s.layers.size(), t.layers.size());
    for (size_t j = 0; j < s.layers.size(); ++j) expect_same(s.layers[j], t.layers[j]);
  }
}

TEST(ReportJson, RoundTripsEveryField) {
  const RunResult run = test::sample_run();
  const auto dir = std::filesystem::temp_directory_path() / "vesper-report-json-test";
  std::filesystem::create_directories(dir);
  write_report_json(run, dir / "report.json");
  expect_same(read_report_json(dir / "report.json"), run);
  EXPECT_FALSE(std::filesystem::exists(dir / "report.json.tmp"));
  std::filesystem::remove_all(dir);
}

TEST(ReportJson, HasTheDocumentedKeys) {
  const nlohmann::json j = report_to_json(test::sample_run());
  EXPECT_EQ(j["format"], "vesper-regress-report/1");
  EXPECT_EQ(j["verdict"], "error");
  const auto& scene = j["scenes"][0];
  EXPECT_EQ(scene["name"], "cornell");
  EXPECT_EQ(scene["verdict"], "regressed");
  const auto& beauty = scene["layers"][0];
  EXPECT_EQ(beauty["worst"][0]["relative_change"], -0.031);
  EXPECT_EQ(beauty["nonfinite"]["introduced_at"][1], nlohmann::json({7, 8}));
  EXPECT_EQ(beauty["significance"]["tiles_x"], 4);
  EXPECT_EQ(beauty["significance"]["z"].size(), 12u);
}

TEST(ReportJson, NonFiniteNumbersBecomeNullAndReadBackAsNan) {
  RunResult run = test::sample_run();
  run.scenes[0].layers[0].max_abs_z = INFINITY;
  const nlohmann::json j = report_to_json(run);
  EXPECT_TRUE(j["scenes"][0]["layers"][0]["max_abs_z"].is_null());
  EXPECT_TRUE(std::isnan(report_from_json(j, "r.json").scenes[0].layers[0].max_abs_z));
}

TEST(ReportJson, ADamagedReportNamesThePath) {
  nlohmann::json j = report_to_json(test::sample_run());
  j["scenes"][0]["layers"][0]["verdict"] = "fine";
  try {
    report_from_json(j, "report.json");
    FAIL() << "accepted";
  } catch (const JsonError& e) {
    EXPECT_EQ(e.file(), "report.json");
    EXPECT_EQ(e.json_path(), "/scenes/0/layers/0/verdict");
  }
  j = report_to_json(test::sample_run());
  j["format"] = "vesper-regress-report/9";
  EXPECT_THROW(report_from_json(j, "report.json"), JsonError);
}

}  // namespace
}  // namespace vesper::regress
