// The job lifecycle over the API (docs/farm.md, "Job lifecycle"): states
// done / failed / canceled, the times of a job and of its tasks' last
// attempts on the server's clock, an ETA while active, and the log tail a
// worker sends with its result (optional: a worker without it completes).
#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

using LifecycleTest = ServerTest;

TEST_F(LifecycleTest, TimesAttemptsEtaAndStatesOverTheApi) {
  start();
  const std::string w = register_worker("w");
  const int64_t job = submit(3);
  json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("state"), "active");
  EXPECT_EQ(j.at("submitted"), 1000);
  EXPECT_FALSE(j.contains("started"));
  EXPECT_FALSE(j.contains("eta")) << "nothing rendered yet";
  EXPECT_EQ(j.at("now"), 1000);

  advance(10);
  const json a = lease(w);
  advance(4);
  post_ok("/complete",
          {{"lease_id", a.at("lease_id")}, {"result", put_blob("f1")}, {"log", "rendered f1"}},
          wrk());
  j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("started"), 1010);
  EXPECT_EQ(j.at("eta"), 8) << "1 task rendered in 4 s since the start, 2 left";
  const json& t = j.at("tasks").at(0);
  EXPECT_EQ(t.at("attempts"), 1);
  EXPECT_EQ(t.at("started"), 1010);
  EXPECT_EQ(t.at("finished"), 1014);
  EXPECT_EQ(t.at("duration"), 4);
  EXPECT_TRUE(t.at("has_log").get<bool>());
  EXPECT_EQ(
      client()
          .Get(("/api/v1/jobs/" + std::to_string(job) + "/tasks/" + t.at("id").dump() + "/log")
                   .c_str(),
               sub())
          ->body,
      "rendered f1");
  const json list = get_ok("/jobs");
  EXPECT_EQ(list.at("now"), 1014);
  EXPECT_EQ(list.at("jobs").at(0).at("eta"), 8);

  // A worker that sends no log still completes (its task has none); a long
  // log keeps its last 16 KiB.
  const json b = lease(w);
  post_ok("/complete", {{"lease_id", b.at("lease_id")}, {"result", put_blob("f2")}}, wrk());
  const json c = lease(w);
  const std::string long_log = std::string(20000, 'x') + "the end";
  advance(1);
  post_ok("/complete",
          {{"lease_id", c.at("lease_id")}, {"result", put_blob("f3")}, {"log", long_log}}, wrk());
  j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_FALSE(j.at("tasks").at(1).at("has_log").get<bool>());
  const std::string kept = client()
                               .Get(("/api/v1/jobs/" + std::to_string(job) + "/tasks/" +
                                     j.at("tasks").at(2).at("id").dump() + "/log")
                                        .c_str(),
                                    sub())
                               ->body;
  EXPECT_EQ(kept.size(), 16u * 1024);
  EXPECT_EQ(kept.substr(kept.size() - 7), "the end");
  EXPECT_EQ(j.at("state"), "done");
  EXPECT_EQ(j.at("finished"), 1015);
  EXPECT_FALSE(j.contains("eta"));
}

TEST_F(LifecycleTest, AFullyFailedJobIsFailedUntilRetried) {
  start();
  const std::string w = register_worker("w");
  const int64_t job = submit(2, 8, 0, 1);
  for (int i = 0; i < 2; ++i)
    post_ok("/fail", {{"lease_id", lease(w).at("lease_id")}, {"log", "crash"}}, wrk());
  json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("state"), "failed");
  EXPECT_TRUE(j.contains("finished"));
  const json r = post_ok("/jobs/" + std::to_string(job) + "/retry-failed", json::object(), sub());
  EXPECT_EQ(r.at("requeued"), 2);
  EXPECT_EQ(r.at("job").at("state"), "active");
  EXPECT_FALSE(r.at("job").contains("finished"));
  const json l = lease(w);
  EXPECT_EQ(l.at("task").at("attempt"), 2) << "every lease counts";
}

}  // namespace
}  // namespace vesper
