// The SQLite job store: leases with fencing, retries, blocklist, cancel and
// pause, persistence across reopen, and atomicity when a process dies
// inside a transaction.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "jobs/job_store.h"
#include "jobs/sqlite_db.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {

class JobStoreTest : public ::testing::Test {
 protected:
  fs::path db() const { return dir_ / "jobs.sqlite"; }
  static JobSpec spec(std::vector<int> frames, int spp = 8, int split = 0, int priority = 50,
                      int attempts = 3) {
    return JobSpec{
        "job", "scene-sha", std::move(frames), spp, split, priority, attempts, {}, {}, {}, {}, {}};
  }
  test::TempDir dir_{"jobs"};
};

TEST_F(JobStoreTest, SubmitSplitsFramesIntoSampleRanges) {
  JobStore s(db());
  const int64_t j = s.submit(spec({1, 2}, 10, 4), 0);
  const auto tasks = s.tasks(j);
  ASSERT_EQ(tasks.size(), 6u);
  EXPECT_EQ(tasks[0].sample_begin, 0);
  EXPECT_EQ(tasks[0].sample_end, 4);
  EXPECT_EQ(tasks[2].sample_begin, 8);
  EXPECT_EQ(tasks[2].sample_end, 10);  // the last range is short
  EXPECT_EQ(tasks[3].frame, 2);
  EXPECT_EQ(s.job(j)->queued, 6);
  EXPECT_EQ(s.schema_version(), 13);
}

TEST_F(JobStoreTest, LeasesByPriorityThenAgeThenFrame) {
  JobStore s(db());
  const int64_t low = s.submit(spec({5, 1}, 8, 0, 10), 0);
  const int64_t high = s.submit(spec({3}, 8, 0, 90), 1);
  auto a = s.lease("w1", 2);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->task.job_id, high);
  auto b = s.lease("w1", 2);
  EXPECT_EQ(b->task.job_id, low);
  EXPECT_EQ(b->task.frame, 1);
  EXPECT_NE(a->lease_id, b->lease_id);
  EXPECT_EQ(a->scene, "scene-sha");
  EXPECT_TRUE(s.lease("w2", 2));
  EXPECT_FALSE(s.lease("w2", 2));  // nothing left
}

TEST_F(JobStoreTest, ExpiredLeaseIsRequeuedAndTheLateUploadRefused) {
  JobStore s(db(), StoreOptions{10, 3});
  const int64_t j = s.submit(spec({1}), 0);
  const auto dead = s.lease("w-dead", 0);
  ASSERT_TRUE(dead);
  EXPECT_FALSE(s.lease("w2", 5));        // still leased
  const auto again = s.lease("w2", 11);  // expired at 10: requeued and re-leased
  ASSERT_TRUE(again);
  EXPECT_EQ(again->task.id, dead->task.id);
  EXPECT_EQ(again->task.attempts, 2);                    // every lease counts
  EXPECT_FALSE(s.complete(dead->lease_id, "late", 12));  // fencing
  EXPECT_EQ(s.heartbeat(dead->lease_id, 12), HeartbeatAnswer::StaleLease);
  EXPECT_TRUE(s.complete(again->lease_id, "good", 12));
  EXPECT_FALSE(s.complete(again->lease_id, "twice", 13));  // committed once
  EXPECT_EQ(s.tasks(j)[0].result, "good");
  EXPECT_TRUE(s.job(j)->finished());
}

TEST_F(JobStoreTest, HeartbeatExtendsTheLease) {
  JobStore s(db(), StoreOptions{10, 3});
  s.submit(spec({1}), 0);
  const auto l = s.lease("w", 0);
  EXPECT_EQ(s.heartbeat(l->lease_id, 8), HeartbeatAnswer::KeepRunning);  // now expires at 18
  EXPECT_EQ(s.expire_leases(15), 0);
  EXPECT_EQ(s.expire_leases(19), 1);
}

TEST_F(JobStoreTest, FailuresRetryThenFailWithTheLogAndBlockTheWorker) {
  JobStore s(db(), StoreOptions{60, 2});
  const int64_t j = s.submit(spec({1, 2, 3}, 8, 0, 50, 3), 0);
  // w-bad fails two different tasks: it is then blocked for this job.
  auto l = s.lease("w-bad", 0);
  ASSERT_EQ(l->task.frame, 1);
  EXPECT_TRUE(s.fail(l->lease_id, "segfault in frame 1", 1));
  EXPECT_FALSE(s.blocked(j, "w-bad"));
  l = s.lease("w-bad", 2);
  ASSERT_EQ(l->task.frame, 2) << "a retry should go to a task this worker has not failed";
  EXPECT_TRUE(s.fail(l->lease_id, "segfault in frame 2", 3));
  EXPECT_TRUE(s.blocked(j, "w-bad"));
  EXPECT_EQ(s.blocked_workers(j), std::vector<std::string>{"w-bad"});
  EXPECT_FALSE(s.lease("w-bad", 4));
  // w-good fails frame 1 (attempt 2), renders 2 and 3, then fails frame 1 again
  // (attempt 3 of 3): the task is failed with its last log, and a worker that
  // failed one task twice is not blocked.
  l = s.lease("w-good", 5);
  ASSERT_EQ(l->task.frame, 1);
  EXPECT_TRUE(s.fail(l->lease_id, "segfault, second time", 6));
  for (int frame : {2, 3}) {
    l = s.lease("w-good", 7);
    ASSERT_EQ(l->task.frame, frame);
    EXPECT_TRUE(s.complete(l->lease_id, "ok", 8));
  }
  l = s.lease("w-good", 9);
  ASSERT_EQ(l->task.frame, 1);
  EXPECT_TRUE(s.fail(l->lease_id, "segfault, third time", 10));
  EXPECT_FALSE(s.blocked(j, "w-good"));
  const auto tasks = s.tasks(j);
  EXPECT_EQ(tasks[0].state, TaskState::Failed);
  EXPECT_EQ(tasks[0].attempts, 3);
  EXPECT_EQ(tasks[0].log, "segfault, third time");
  EXPECT_TRUE(s.job(j)->finished());
  EXPECT_EQ(s.job(j)->failed, 1);
  // retry-failed requeues it and lifts the blocklist.
  EXPECT_EQ(s.retry_failed(j), 1);
  EXPECT_FALSE(s.blocked(j, "w-bad"));
  EXPECT_TRUE(s.lease("w-bad", 11));
}

TEST_F(JobStoreTest, IdenticalTasksAreRenderedOnceByTheSameRenderer) {
  JobStore s(db(), StoreOptions{60, 3});
  JobSpec a = spec({1, 2}, 8);
  a.assets = {{"assets/cube.obj", std::string(64, 'c')}};
  const int64_t first = s.submit(a, 0);
  for (int i = 0; i < 2; ++i) {
    const auto l = s.lease("w", 1, "r1");
    ASSERT_TRUE(l);
    EXPECT_TRUE(s.complete(l->lease_id, "result-" + std::to_string(l->task.frame), 2));
  }
  // The same inputs again (assets in another order would be the same too):
  // frame 1 and 2 are done at once with the first job's results; frame 3 is new.
  JobSpec b = a;
  b.frames = {1, 2, 3};
  const int64_t second = s.submit(b, 3);
  int reused = -1;
  const auto l = s.lease("w", 4, "r1", &reused);
  ASSERT_TRUE(l);
  EXPECT_EQ(reused, 2);
  EXPECT_EQ(l->task.frame, 3);
  const auto tasks = s.tasks(second);
  EXPECT_EQ(tasks[0].state, TaskState::Done);
  EXPECT_EQ(tasks[0].result, "result-1");
  EXPECT_EQ(tasks[1].result, "result-2");
  EXPECT_EQ(tasks[0].reused_from, s.tasks(first)[0].id);
  EXPECT_EQ(tasks[2].reused_from, 0);

  // Another renderer, other spp, another asset or no renderer id: rendered again.
  JobSpec c = a;
  c.assets[0].blob = std::string(64, 'd');
  const int64_t other_asset = s.submit(c, 5);
  JobSpec d = a;
  d.spp = 16;
  const int64_t other_spp = s.submit(d, 5);
  const int64_t other_renderer = s.submit(a, 5);
  for (const int64_t job : {other_asset, other_spp}) {
    const auto m = s.lease("w", 6, "r1", &reused);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->task.job_id, job);
    EXPECT_EQ(reused, 0);
    EXPECT_TRUE(s.complete(m->lease_id, "x", 7));
    const auto n = s.lease("w", 6, "r1");
    EXPECT_TRUE(s.complete(n->lease_id, "x", 7));
  }
  const auto m = s.lease("w", 8, "r2", &reused);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->task.job_id, other_renderer);
  EXPECT_EQ(reused, 0);
  const auto n = s.lease("w", 8, "", &reused);
  ASSERT_TRUE(n);
  EXPECT_EQ(n->task.job_id, other_renderer);
  EXPECT_EQ(reused, 0);
}

// A job's render overrides reach each lease, and are part of what makes
// tasks identical: the same scene with other AOVs, another seed or half-float
// channels is another result.
TEST_F(JobStoreTest, RenderOverridesAreLeasedAndKeyResultReuse) {
  JobStore s(db(), StoreOptions{60, 3});
  JobSpec a = spec({1}, 8);
  a.overrides = {{"variance", "albedo"}, true, 7, 0.25};
  s.submit(a, 0);
  const auto l = s.lease("w", 1, "r1");
  ASSERT_TRUE(l);
  EXPECT_EQ(l->overrides, a.overrides);
  EXPECT_TRUE(s.complete(l->lease_id, "with-overrides", 2));

  int reused = -1;
  const int64_t same = s.submit(a, 3);
  EXPECT_FALSE(s.lease("w", 4, "r1", &reused));  // done at once with the first result
  EXPECT_EQ(reused, 1);
  EXPECT_EQ(s.tasks(same)[0].result, "with-overrides");
  for (auto change : std::vector<std::function<void(RenderOverrides&)>>{
           [](RenderOverrides& o) { o.aovs = {"variance"}; },
           [](RenderOverrides& o) { o.layer_variance = false; },
           [](RenderOverrides& o) { o.seed = 8; }, [](RenderOverrides& o) { o.scale.reset(); },
           [](RenderOverrides& o) { o.half = true; }}) {
    JobSpec b = a;
    change(b.overrides);
    const int64_t other = s.submit(b, 5);
    const auto m = s.lease("w", 6, "r1", &reused);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->task.job_id, other);
    EXPECT_EQ(m->overrides, b.overrides);
    EXPECT_EQ(reused, 0);
    EXPECT_TRUE(s.complete(m->lease_id, "x", 7));
  }
  // A job without overrides leases without them (as before they existed).
  s.submit(spec({2}, 8), 8);
  const auto plain = s.lease("w", 9, "r1");
  ASSERT_TRUE(plain);
  EXPECT_TRUE(plain->overrides.empty());
  JobSpec bad = a;
  bad.overrides.scale = 5;
  EXPECT_THROW(s.submit(bad, 10), StoreError);
}

// Pause stops leasing and lets running tasks finish (their results are
// taken); cancel stops running tasks at their next heartbeat.
TEST_F(JobStoreTest, PauseLetsRunningTasksFinishAndCancelStopsThem) {
  JobStore s(db());
  const int64_t j = s.submit(spec({1, 2, 3}), 0);
  const auto running = s.lease("w", 0);
  EXPECT_TRUE(s.pause(j));
  EXPECT_EQ(s.heartbeat(running->lease_id, 1), HeartbeatAnswer::KeepRunning);
  EXPECT_FALSE(s.lease("w", 1));
  EXPECT_TRUE(s.complete(running->lease_id, "x", 1));
  EXPECT_EQ(s.job(j)->paused, 2);
  EXPECT_EQ(s.job(j)->done, 1);
  EXPECT_TRUE(s.resume(j));
  const auto l = s.lease("w", 2);
  ASSERT_TRUE(l);
  EXPECT_TRUE(s.cancel(j, 3));
  EXPECT_EQ(s.heartbeat(l->lease_id, 3), HeartbeatAnswer::Stop);
  EXPECT_FALSE(s.complete(l->lease_id, "late", 4));
  EXPECT_EQ(s.job(j)->canceled, 2);
  EXPECT_TRUE(s.job(j)->finished());
  EXPECT_FALSE(s.cancel(999, 5));
}

TEST_F(JobStoreTest, CommittedStateSurvivesReopening) {
  int64_t j = 0;
  std::string lease_id;
  {
    JobStore s(db());
    j = s.submit(spec({1, 2}), 0);
    const auto a = s.lease("w", 0);
    EXPECT_TRUE(s.complete(a->lease_id, "frame1.exr", 1));
    lease_id = s.lease("w", 1)->lease_id;
  }
  JobStore s(db());
  EXPECT_EQ(s.job(j)->done, 1);
  EXPECT_EQ(s.job(j)->leased, 1);
  EXPECT_EQ(s.tasks(j)[0].result, "frame1.exr");
  EXPECT_TRUE(s.complete(lease_id, "frame2.exr", 2));  // the lease is still valid after a restart
}

TEST_F(JobStoreTest, AProcessKilledInsideATransactionLeavesNoTrace) {
  { JobStore s(db()); }
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // Child: write inside a transaction and die without committing (like kill -9).
    try {
      sql::Db db(this->db().string());
      db.exec("BEGIN IMMEDIATE");
      db.exec(
          "INSERT INTO jobs(name, scene, spp, priority, max_attempts, state, created) "
          "VALUES('ghost', 's', 1, 1, 1, 'active', 0)");
    } catch (...) {
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  JobStore s(db());
  EXPECT_TRUE(s.jobs().empty());
  EXPECT_NO_THROW(s.submit(spec({1}), 0));  // and the database is not locked
}

TEST_F(JobStoreTest, ANewerSchemaIsRefused) {
  { JobStore s(db()); }
  {
    sql::Db raw(db().string());
    raw.exec("UPDATE schema_version SET version = 99");
  }
  EXPECT_THROW(JobStore s(db()), StoreError);
}

TEST_F(JobStoreTest, AssetsAreStoredInOrderAndCarriedByTheLease) {
  JobStore s(db());
  JobSpec sp = spec({1, 2});
  sp.assets = {{"assets/cube.obj", std::string(64, 'a')}, {"env.exr", std::string(64, 'b')}};
  const int64_t j = s.submit(sp, 0);
  EXPECT_EQ(s.assets(j), sp.assets);
  const auto l = s.lease("w", 0);
  ASSERT_TRUE(l);
  EXPECT_EQ(l->assets, sp.assets);
  // A job without assets leases none.
  const int64_t k = s.submit(spec({1}, 8, 0, 99), 0);
  const auto m = s.lease("w", 0);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->task.job_id, k);
  EXPECT_TRUE(m->assets.empty());
  // The store refuses names that could escape the scene directory.
  for (const char* bad : {"../x", "/etc/passwd", "a/../../b", "a//b", "", "a\\b", "./a", "a/"}) {
    JobSpec b = spec({1});
    b.assets = {{bad, std::string(64, 'c')}};
    EXPECT_THROW(s.submit(b, 0), StoreError) << bad;
  }
}

TEST_F(JobStoreTest, AssetNames) {
  EXPECT_EQ(asset_name_problem("assets/cube.obj"), "");
  EXPECT_EQ(asset_name_problem("a.b/..c/d..e"), "");
  EXPECT_EQ(asset_name_problem(std::string(255, 'x')), "");
  for (const std::string& bad :
       std::vector<std::string>{"", "../x", "/etc/passwd", "a/../../b", "a//b", "a\\b", "./a", "a/",
                                ".", "..", std::string(256, 'x'), std::string("a\0b", 3)})
    EXPECT_NE(asset_name_problem(bad), "") << bad;
}

TEST_F(JobStoreTest, AOneTaskFrameRecordsItsOutputOnCompletion) {
  JobStore s(db());
  const int64_t j = s.submit(spec({1, 2}, 8, 4), 0);  // two tasks per frame
  const int64_t k = s.submit(spec({7}), 0);           // one task
  EXPECT_EQ(s.frames(j).size(), 2u);
  while (auto l = s.lease("w", 1)) s.complete(l->lease_id, "r" + std::to_string(l->task.id), 1);
  const auto f7 = s.frame(k, 7);
  ASSERT_TRUE(f7);
  EXPECT_TRUE(f7->complete());
  EXPECT_EQ(f7->output, f7->results.at(0));  // recorded with the completion
  const auto f1 = s.frame(j, 1);
  ASSERT_TRUE(f1);
  EXPECT_TRUE(f1->complete());
  EXPECT_EQ(f1->tasks, 2);
  EXPECT_EQ(f1->results.size(), 2u);
  EXPECT_EQ(f1->output, "");  // a merge is needed
  EXPECT_EQ(s.frames_awaiting_merge(), (std::vector<std::pair<int64_t, int>>{{j, 1}, {j, 2}}));
  EXPECT_FALSE(s.frame(j, 3));
  // Recorded once: a second (racing) merge keeps the first output.
  EXPECT_EQ(s.record_frame_output(j, 1, "merged-a", 2), "merged-a");
  EXPECT_EQ(s.record_frame_output(j, 1, "merged-b", 3), "merged-a");
  EXPECT_EQ(s.frame(j, 1)->output, "merged-a");
  EXPECT_EQ(s.frames(j).at(1).output, "");
  EXPECT_EQ(s.frames_awaiting_merge(), (std::vector<std::pair<int64_t, int>>{{j, 2}}));
}

TEST_F(JobStoreTest, AnUnfinishedFrameHasNoOutput) {
  JobStore s(db());
  const int64_t j = s.submit(spec({1}, 8, 4), 0);
  const auto l = s.lease("w", 0);
  s.complete(l->lease_id, "r", 1);
  EXPECT_FALSE(s.frame(j, 1)->complete());
  EXPECT_THROW(s.record_frame_output(j, 1, "m", 2), StoreError);
  EXPECT_TRUE(s.frames_awaiting_merge().empty());
}

TEST_F(JobStoreTest, AVersion1DatabaseMigrates) {
  // The schema as migration 1 created it, with a job in it.
  {
    sql::Db raw(db().string());
    raw.exec(R"sql(
CREATE TABLE schema_version(version INTEGER NOT NULL);
INSERT INTO schema_version(version) VALUES(1);
CREATE TABLE jobs(
  id INTEGER PRIMARY KEY, name TEXT NOT NULL, scene TEXT NOT NULL, spp INTEGER NOT NULL,
  priority INTEGER NOT NULL, max_attempts INTEGER NOT NULL, state TEXT NOT NULL, created REAL NOT NULL);
CREATE TABLE tasks(
  id INTEGER PRIMARY KEY, job_id INTEGER NOT NULL REFERENCES jobs(id), frame INTEGER NOT NULL,
  sample_begin INTEGER NOT NULL, sample_end INTEGER NOT NULL, state TEXT NOT NULL,
  attempts INTEGER NOT NULL DEFAULT 0, lease_id TEXT, worker TEXT NOT NULL DEFAULT '',
  lease_expiry REAL, result TEXT NOT NULL DEFAULT '', log TEXT NOT NULL DEFAULT '');
CREATE INDEX tasks_by_state ON tasks(state, job_id);
CREATE UNIQUE INDEX tasks_by_lease ON tasks(lease_id) WHERE lease_id IS NOT NULL;
CREATE TABLE worker_failures(
  job_id INTEGER NOT NULL, worker TEXT NOT NULL, failures INTEGER NOT NULL, PRIMARY KEY(job_id, worker));
INSERT INTO jobs VALUES(1, 'old', 'scene-sha', 8, 50, 3, 'active', 0);
INSERT INTO tasks(job_id, frame, sample_begin, sample_end, state, result) VALUES(1, 1, 0, 8, 'done', 'r1');
INSERT INTO tasks(job_id, frame, sample_begin, sample_end, state) VALUES(1, 2, 0, 8, 'queued');
)sql");
  }
  JobStore s(db());
  EXPECT_EQ(s.schema_version(), 13);
  EXPECT_EQ(s.job(1)->name, "old");
  EXPECT_TRUE(s.assets(1).empty());
  EXPECT_TRUE(s.frame(1, 1)->complete());
  EXPECT_EQ(s.frame(1, 1)->output, "");  // completed before outputs were recorded
  const auto l = s.lease("w", 1);
  ASSERT_TRUE(l);
  EXPECT_EQ(l->task.frame, 2);
  EXPECT_TRUE(l->assets.empty());
  EXPECT_TRUE(l->overrides.empty());  // an old job renders as it always did
  EXPECT_TRUE(s.complete(l->lease_id, "r2", 2));
  EXPECT_EQ(s.frame(1, 2)->output, "r2");
  JobSpec sp = spec({1});
  sp.assets = {{"a.obj", std::string(64, 'a')}};
  const int64_t j = s.submit(sp, 3);
  EXPECT_EQ(s.assets(j), sp.assets);
}

}  // namespace
TEST_F(JobStoreTest, ALeaseCarriesItsJobsTaskTimeout) {
  JobStore s(db());
  JobSpec timed = spec({1});
  timed.task_timeout = 90;
  s.submit(timed, 0);
  s.submit(spec({1}), 0);
  EXPECT_EQ(s.lease("w", 1)->task_timeout, 90);
  EXPECT_FALSE(s.lease("w", 1)->task_timeout);  // unset: the server's default applies
  JobSpec bad = spec({1});
  bad.task_timeout = 0;
  EXPECT_THROW(s.submit(bad, 0), StoreError);
}

// A server that was down renews the leases it finds when it starts: no
// worker could heartbeat meanwhile, so none is lost (or charged) for that.
TEST_F(JobStoreTest, RenewedLeasesOutliveTheServersAbsence) {
  JobStore s(db(), StoreOptions{60, 3});
  s.submit(spec({1, 2}), 0);
  const auto held = s.lease("w", 0);  // expires at 60
  ASSERT_TRUE(held);
  EXPECT_EQ(s.renew_leases(100), 1);  // a restart at 100, after a 100 s outage
  EXPECT_EQ(s.expire_leases(150), 0);
  EXPECT_EQ(s.heartbeat(held->lease_id, 150), HeartbeatAnswer::KeepRunning);
  EXPECT_TRUE(s.complete(held->lease_id, "r", 151));
  EXPECT_EQ(s.tasks(1)[0].attempts, 1);
  // A lease nobody renews still expires, and its task is requeued.
  const auto lost = s.lease("w", 200);
  EXPECT_EQ(s.expire_leases(261), 1);
  EXPECT_EQ(s.tasks(1)[1].attempts, 1);
  EXPECT_FALSE(s.complete(lost->lease_id, "r", 262));
}

}  // namespace vesper
