// The SQLite history: runs are recorded whole, a scene's trend comes back
// oldest first with its layers, the median render time skips reused runs,
// the file is in WAL mode, and a newer schema is refused naming the file.
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <filesystem>

#include "regress/history.h"
#include "regress_dir_test.h"
#include "sample_results.h"

namespace vesper::regress {
namespace {

namespace fs = std::filesystem;

using HistoryTest = test::RegressDirTest;

RunResult run_with_time(const std::string& started_at, double seconds, bool reused = false) {
  RunResult run = test::sample_run();
  run.started_at = started_at;
  run.scenes[0].new_seconds = seconds;
  run.scenes[0].reused = reused;
  return run;
}

TEST_F(HistoryTest, RecordsRunsAndReturnsTheTrendOldestFirst) {
  History h(dir_ / "history.db");
  const int64_t first = h.record(run_with_time("2024-05-01T02:00:00Z", 2.0));
  h.record(run_with_time("2024-05-02T02:00:00Z", 3.0));
  const int64_t last = h.record(run_with_time("2024-05-03T02:00:00Z", 4.0));
  EXPECT_LT(first, last);
  const std::vector<TrendPoint> all = h.trend("cornell", 10);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].started_at, "2024-05-01T02:00:00Z");
  // What the report draws is what trend_point makes of the scene.
  const TrendPoint expected = trend_point(run_with_time("", 4.0).scenes[0], "2024-05-03T02:00:00Z");
  const TrendPoint& p = all[2];
  EXPECT_EQ(p.scene, "cornell");
  EXPECT_EQ(p.started_at, expected.started_at);
  EXPECT_EQ(p.verdict, Verdict::Regressed);
  EXPECT_EQ(p.render_seconds, 4.0);
  EXPECT_FALSE(p.reused);
  EXPECT_EQ(p.max_abs_z, expected.max_abs_z);
  EXPECT_EQ(p.min_detectable_change, expected.min_detectable_change);
  EXPECT_EQ(p.min_detectable_change, 0.021);
  EXPECT_EQ(p.histogram_distance, expected.histogram_distance);
  const std::vector<TrendPoint> two = h.trend("cornell", 2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].started_at, "2024-05-02T02:00:00Z");
  const std::vector<TrendPoint> smoke = h.trend("smoke", 10);
  ASSERT_EQ(smoke.size(), 3u);
  EXPECT_TRUE(smoke[0].reused);
  EXPECT_EQ(smoke[0].render_seconds, 0);  // reused: no render, no time
  EXPECT_EQ(smoke[0].verdict, Verdict::Error);
  EXPECT_TRUE(h.trend("nope", 10).empty());
}

TEST_F(HistoryTest, RecentTrendsHoldEverySceneOfTheLastRuns) {
  History h(dir_ / "history.db");
  h.record(run_with_time("a", 2.0));
  h.record(run_with_time("b", 3.0));
  h.record(run_with_time("c", 4.0));
  const std::vector<TrendPoint> points = h.recent_trends(2);
  ASSERT_EQ(points.size(), 4u);  // runs b and c, cornell and smoke each
  EXPECT_EQ(points[0].started_at, "b");
  EXPECT_EQ(points[0].scene, "cornell");
  EXPECT_EQ(points[1].scene, "smoke");
  EXPECT_EQ(points[3].started_at, "c");
  EXPECT_EQ(points[2].render_seconds, 4.0);
}

TEST_F(HistoryTest, MedianTimeSkipsReusedRunsAndPersists) {
  {
    History h(dir_ / "history.db");
    EXPECT_FALSE(h.median_seconds("cornell", 5));
    h.record(run_with_time("a", 2.0));
    h.record(run_with_time("b", 9.0, true));  // reused: nothing was rendered
    h.record(run_with_time("c", 4.0));
    h.record(run_with_time("d", 3.0));
  }
  History again(dir_ / "history.db");  // reopened: the schema is not applied twice
  EXPECT_EQ(again.median_seconds("cornell", 5), 3.0);
  EXPECT_EQ(again.median_seconds("cornell", 2), 3.5);  // d and c
}

TEST_F(HistoryTest, UsesWalAndRefusesANewerSchemaNamingTheFile) {
  const fs::path file = dir_ / "history.db";
  { History h(file); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &s, nullptr);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)), "wal");
  sqlite3_finalize(s);
  sqlite3_exec(db, "UPDATE schema_version SET version = 99", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  try {
    History h(file);
    FAIL() << "a newer schema was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("regression history " + file.string() +
                                         " has schema version 99"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(HistoryTest, AnUnopenableFileIsNamed) {
  const fs::path file = dir_ / "no-such-dir" / "history.db";
  try {
    History h(file);
    FAIL() << "opened " << file;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("regression history " + file.string()), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vesper::regress
