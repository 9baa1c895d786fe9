// The CLI reads a big job's every task page (issue 17, item 9): `vesper
// status JOB --json` of a job longer than one page (10 000 tasks) holds all
// its tasks and frames once each, joined from the server's pages.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <set>

#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

TEST_F(FarmTest, StatusJoinsEveryPageOfABigJob) {
  const auto config = write_config(60);
  const auto scene = write_scene(8, 8, 2);
  start_server(config);
  // 5 001 frames in two sample ranges each: 10 002 tasks, two pages, frame
  // 5 001 split over the page boundary.
  const long long id = submit(scene.string() + " --frames 1-5001 --split 1 --name big");
  ASSERT_GT(id, 0);
  ASSERT_TRUE(job(id).contains("tasks_next")) << "the job fits one page: the test tests nothing";
  const RunResult r = farm(fmt::format("status {} --json", id));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j.contains("tasks_next"));
  ASSERT_EQ(j.at("tasks").size(), 10002u);
  std::set<long long> ids;
  for (const auto& t : j.at("tasks")) ids.insert(t.at("id").get<long long>());
  EXPECT_EQ(ids.size(), 10002u);
  ASSERT_EQ(j.at("frames").size(), 5001u);
  for (size_t i = 0; i < 5001; ++i) {
    EXPECT_EQ(j.at("frames").at(i).at("frame"), int(i) + 1);
    EXPECT_EQ(j.at("frames").at(i).at("tasks"), 2);
  }
  const RunResult text = farm(fmt::format("status {}", id));
  EXPECT_EQ(text.exit_code, 0) << text.err;
  // The table has a row per task, from both pages.
  size_t rows = 0;
  for (size_t at = text.out.find("[1, 2)"); at != std::string::npos;
       at = text.out.find("[1, 2)", at + 1))
    ++rows;
  EXPECT_EQ(rows, 5001u) << text.out.substr(0, 400);
}

}  // namespace
}  // namespace vesper::test
