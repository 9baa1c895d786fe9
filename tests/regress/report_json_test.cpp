// report.json keeps every field of a RunResult and reads back what it wrote;
// a damaged report is rejected with the JSON path of the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/json_error.h"
#include "regress/report_json.h"
#include "sample_results.h"
#include "tests/common/temp_dir.h"

namespace vesper::regress {
namespace {

// Every field of sample_run() is set, so equal JSON means nothing was lost;
// a few fields are checked on the struct itself.
void expect_same(const RunResult& read, const RunResult& written) {
  EXPECT_EQ(report_to_json(read), report_to_json(written));
  ASSERT_EQ(read.scenes.size(), 2u);
  const LayerResult& b = read.scenes[0].layers[0];
  EXPECT_EQ(b.introduced_nonfinite_at[1].y, 8);
  EXPECT_EQ(b.worst[0].p_value, 6e-13);
  EXPECT_EQ(b.tile_z, written.scenes[0].layers[0].tile_z);
  EXPECT_EQ(b.tile_significant, written.scenes[0].layers[0].tile_significant);
  EXPECT_TRUE(read.scenes[1].reused);
}

TEST(ReportJson, RoundTripsEveryField) {
  const RunResult run = test::sample_run();
  const test::TempDir dir("regress");
  write_report_json(run, dir / "report.json");
  expect_same(read_report_json(dir / "report.json"), run);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}),
            1);  // no temporary left
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
  EXPECT_EQ(beauty["significance"]["significant"][1], 1);
}

// "server" and "render_time_note" were added within /1: older reports lack them.
TEST(ReportJson, ReadsAReportWithoutTheFarmKeys) {
  nlohmann::json j = report_to_json(test::sample_run());
  EXPECT_EQ(j["server"], "http://farm:8765");
  j.erase("server");
  j.erase("render_time_note");
  const RunResult run = report_from_json(j, "old.json");
  EXPECT_TRUE(run.server.empty());
  EXPECT_TRUE(run.render_time_note.empty());
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
