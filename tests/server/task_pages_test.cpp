// GET /jobs/{id} reads a big job's task list in pages (issue 17, item 9):
// tasks in leasing order by id, `tasks_next` until the last page, the frames
// of each page's tasks, 400 for a bad page parameter; and listings read on
// their own connection, so they see committed state only.
#include <gtest/gtest.h>

#include <set>

#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

using json = nlohmann::json;

class TaskPagesTest : public ServerTest {};

TEST_F(TaskPagesTest, AJobsTasksComeInPagesWithTheirFrames) {
  start();
  const int64_t job = submit(5, 8, 4);  // 5 frames × 2 sample ranges = 10 tasks
  const std::string path = "/jobs/" + std::to_string(job);
  std::vector<int64_t> ids;
  std::set<int> frames;
  int pages = 0;
  std::string query = "?tasks_limit=4";
  for (;; ++pages) {
    const json page = get_ok(path + query);
    ASSERT_LE(page.at("tasks").size(), 4u);
    for (const json& t : page.at("tasks")) {
      ids.push_back(t.at("id").get<int64_t>());
      // Each page lists the frames of its tasks (and no others).
      bool listed = false;
      for (const json& f : page.at("frames")) listed |= f.at("frame") == t.at("frame");
      EXPECT_TRUE(listed) << "frame " << t.at("frame") << " of page " << pages;
    }
    for (const json& f : page.at("frames")) frames.insert(f.at("frame").get<int>());
    EXPECT_EQ(page.at("total"), 10);  // the summary is the whole job's
    if (!page.contains("tasks_next")) break;
    EXPECT_EQ(page.at("tasks_next"), page.at("tasks").back().at("id"));
    query = "?tasks_limit=4&tasks_after=" + std::to_string(page.at("tasks_next").get<int64_t>());
  }
  EXPECT_EQ(pages + 1, 3);
  ASSERT_EQ(ids.size(), 10u);
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  EXPECT_EQ(frames, (std::set<int>{1, 2, 3, 4, 5}));
  // Without parameters, one page holds them all.
  const json all = get_ok(path);
  EXPECT_EQ(all.at("tasks").size(), 10u);
  EXPECT_FALSE(all.contains("tasks_next"));
}

TEST_F(TaskPagesTest, ABadPageParameterIs400) {
  start();
  const int64_t job = submit(2);
  for (const std::string q :
       {"tasks_limit=0", "tasks_limit=10001", "tasks_limit=x", "tasks_after=-1", "tasks_after=1e3",
        "tasks_after=99999999999999999999"}) {
    auto r = client().Get(("/api/v1/jobs/" + std::to_string(job) + "?" + q).c_str(), sub());
    ASSERT_TRUE(r) << q;
    EXPECT_EQ(r->status, 400) << q << ": " << r->body;
    EXPECT_NE(json::parse(r->body).at("error").get<std::string>().find("query parameter"),
              std::string::npos)
        << r->body;
  }
}

TEST_F(TaskPagesTest, ListingsSeeWhatLeasesAndCompletionsCommitted) {
  start();
  const int64_t job = submit(3);
  const std::string worker = register_worker("w");
  const json l = lease(worker);
  const std::string blob = put_blob("result bytes");
  post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", blob}}, wrk());
  // The listing connection is not the one that wrote: it must see the commit.
  const json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("counts").at("done"), 1);
  EXPECT_EQ(get_ok("/jobs").at("jobs").at(0).at("counts").at("done"), 1);
  auto log = client().Get(("/api/v1/jobs/" + std::to_string(job) + "/tasks/" +
                           std::to_string(l.at("task").at("id").get<int64_t>()) + "/log")
                              .c_str(),
                          sub());
  ASSERT_TRUE(log);
  EXPECT_EQ(log->status, 200);
  auto missing =
      client().Get(("/api/v1/jobs/" + std::to_string(job) + "/tasks/999/log").c_str(), sub());
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
}

}  // namespace
}  // namespace vesper
