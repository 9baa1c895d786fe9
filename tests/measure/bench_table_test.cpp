// The equal-error table: time marks, the peer ratio with its goal, flagged
// references, skipped scenes; and bench.csv/bench.json of the same report.
#include <gtest/gtest.h>

#include "measure/bench_report.h"
#include "measure/bench_table.h"

namespace vesper::measure {
namespace {

RendererRun run(const std::string& name, double floor, TimeToError t1, TimeToError t2) {
  RendererRun r;
  r.renderer = name;
  r.noise_floor = floor;
  r.curve = {{1, 0.1, 0.2, 0.5}, {4, 0.4, 0.5, 0.125}};
  r.times = {{1e-2, t1}, {4e-3, t2}};
  return r;
}

BenchReport report() {
  BenchReport rep;
  rep.targets = {1e-2, 4e-3};
  rep.renderers = {"vesper", "cycles"};
  SceneResult s;
  s.name = "fog";
  s.kind = "volume";
  s.runs = {
      run("vesper", 1e-4, {2.0, TimeEstimate::Interpolated}, {5.0, TimeEstimate::Extrapolated}),
      run("cycles", 3e-3, {4.0, TimeEstimate::Interpolated}, {0.1, TimeEstimate::BelowFirst})};
  PeerComparison c;
  c.peer = "cycles";
  c.ratios = {{1e-2, 0.5, false, 0.5, true}, {4e-3, 50.0, true, 0.5, false}};
  ReferenceAgreement a;
  a.mean_ratio = 1.31;
  a.flagged = true;
  c.agreement = a;
  s.comparisons = {c};
  SceneResult skipped;
  skipped.name = "smoke";
  skipped.kind = "volume";
  skipped.skipped = true;
  skipped.note = "skipped: the scene reads smoke.vdb, which is absent";
  rep.scenes = {s, skipped};
  return rep;
}

TEST(BenchTable, MarksTimesRatiosGoalsAndFlags) {
  const std::string t = bench_table_text(report());
  EXPECT_NE(t.find("2 s"), std::string::npos) << t;
  EXPECT_NE(t.find("~5 s*"), std::string::npos) << t;      // extrapolated
  EXPECT_NE(t.find("< 0.1 s !"), std::string::npos) << t;  // upper bound, floor >= target / 2
  EXPECT_NE(t.find("0.50x (met <= 0.5x)"), std::string::npos) << t;
  EXPECT_NE(t.find("~50.00x (NOT met <= 0.5x)"), std::string::npos) << t;
  EXPECT_NE(t.find("mean 1.310"), std::string::npos) << t;
  EXPECT_NE(t.find("FLAGGED"), std::string::npos) << t;
  EXPECT_NE(t.find("smoke: skipped: the scene reads smoke.vdb"), std::string::npos) << t;
  const std::string md = bench_table_markdown(report());
  EXPECT_NE(md.find("| fog | volume | vesper / cycles |"), std::string::npos) << md;
}

TEST(BenchTable, CsvHasARowPerMeasurementAndJsonTheSameFigures) {
  const std::string csv = bench_csv(report());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4);
  EXPECT_NE(csv.find("fog,volume,cycles,4,0.4,0.5,0.125,0.003,false"), std::string::npos) << csv;
  const nlohmann::json j = bench_json(report());
  EXPECT_EQ(j["format"], "vesper-bench-report/1");
  const auto& times = j["scenes"][0]["renderers"][1]["time_to_error"];
  EXPECT_EQ(times[1]["estimate"], "below_first");
  EXPECT_TRUE(times[1]["reference_limited"].get<bool>());
  EXPECT_EQ(j["scenes"][0]["comparisons"][0]["equal_error_ratios"][0]["goal_met"], true);
  EXPECT_EQ(j["scenes"][1]["note"], "skipped: the scene reads smoke.vdb, which is absent");
}

}  // namespace
}  // namespace vesper::measure
