// Jobs end and say what happened (docs/farm.md, "Job lifecycle"): done,
// failed or canceled, derived when the last task ends, with the times of
// submit, start and finish; tasks count every lease and record their last
// attempt's times and log; a fully reused job ends at submit.
#include <gtest/gtest.h>

#include <filesystem>

#include "jobs/job_store.h"
#include "jobs/migrations.h"
#include "jobs/sqlite_db.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

class JobLifecycleTest : public ::testing::Test {
 protected:
  std::filesystem::path db() const { return dir_ / "jobs.sqlite"; }
  static JobSpec spec(std::vector<int> frames, int max_attempts = 3) {
    JobSpec s;
    s.name = "job";
    s.scene = "scene-sha";
    s.frames = std::move(frames);
    s.spp = 8;
    s.max_attempts = max_attempts;
    return s;
  }
  // Leases the next task and completes it at `t0` + 1.
  static void render_one(JobStore& s, double t0, const std::string& renderer = "") {
    const auto l = s.lease("w", t0, renderer);
    ASSERT_TRUE(l);
    ASSERT_TRUE(s.complete(l->lease_id, "r" + std::to_string(l->task.frame), t0 + 1, {}, "log"));
  }
  test::TempDir dir_{"lifecycle"};
};

TEST_F(JobLifecycleTest, AJobWhoseTasksAreAllDoneEndsDoneWithItsTimes) {
  JobStore s(db());
  const int64_t j = s.submit(spec({1, 2}), 10);
  EXPECT_EQ(s.job(j)->submitted_at, 10);
  EXPECT_FALSE(s.job(j)->started_at);
  const auto a = s.lease("w1", 20);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->task.attempts, 1);
  EXPECT_EQ(s.job(j)->started_at, 20);
  EXPECT_TRUE(s.complete(a->lease_id, "r1", 25, {}, "rendered frame 1"));
  const Task t = s.tasks(j)[0];
  EXPECT_EQ(t.attempts, 1) << "a rendered done task counts its lease";
  EXPECT_EQ(t.started, 20);
  EXPECT_EQ(t.finished, 25);
  EXPECT_EQ(t.worker, "w1");
  EXPECT_EQ(t.log, "rendered frame 1");
  EXPECT_EQ(s.job(j)->state, JobState::Active);
  EXPECT_FALSE(s.job(j)->finished_at);
  render_one(s, 30);
  EXPECT_EQ(s.job(j)->state, JobState::Done);
  EXPECT_EQ(s.job(j)->finished_at, 31);
  EXPECT_EQ(s.job(j)->started_at, 20);
  // A done job stays done: pause, resume, cancel and retry change nothing.
  EXPECT_TRUE(s.pause(j));
  EXPECT_TRUE(s.cancel(j, 40));
  EXPECT_TRUE(s.resume(j));
  EXPECT_EQ(s.retry_failed(j), 0);
  EXPECT_EQ(s.job(j)->state, JobState::Done);
  EXPECT_EQ(s.job(j)->finished_at, 31);
}

TEST_F(JobLifecycleTest, AFullyFailedJobEndsFailedAndRetryMakesItActiveAgain) {
  JobStore s(db(), StoreOptions{60, 10});
  const int64_t j = s.submit(spec({1, 2}, 2), 0);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(s.job(j)->state, JobState::Active);
    const auto l = s.lease("w", 1 + i);
    ASSERT_TRUE(l) << i;
    EXPECT_TRUE(s.fail(l->lease_id, "crash " + std::to_string(i), 1.5 + i));
  }
  const auto failed = s.job(j);
  EXPECT_EQ(failed->state, JobState::Failed);
  EXPECT_EQ(failed->failed, 2);
  EXPECT_EQ(failed->finished_at, 4.5);
  EXPECT_EQ(s.tasks(j)[1].attempts, 2);
  EXPECT_EQ(s.tasks(j)[1].finished, 4.5);
  EXPECT_FALSE(s.lease("w", 5));

  EXPECT_EQ(s.retry_failed(j), 2);
  EXPECT_EQ(s.job(j)->state, JobState::Active);
  EXPECT_FALSE(s.job(j)->finished_at);
  render_one(s, 6);
  render_one(s, 8);
  EXPECT_EQ(s.job(j)->state, JobState::Done);
  EXPECT_EQ(s.job(j)->finished_at, 9);
  EXPECT_EQ(s.tasks(j)[0].attempts, 3) << "attempts count every lease, across retries";
}

TEST_F(JobLifecycleTest, AJobWithADoneAndAFailedTaskEndsFailedWhenNothingIsLeft) {
  JobStore s(db());
  const int64_t j = s.submit(spec({1, 2}, 1), 0);
  const auto a = s.lease("w", 1);
  const auto b = s.lease("w", 1);
  EXPECT_TRUE(s.fail(a->lease_id, "crash", 2));
  EXPECT_EQ(s.job(j)->state, JobState::Active) << "a task is still running";
  EXPECT_TRUE(s.complete(b->lease_id, "r", 3));
  EXPECT_EQ(s.job(j)->state, JobState::Failed);
  EXPECT_EQ(s.job(j)->finished_at, 3);
}

TEST_F(JobLifecycleTest, AnExpiredLastAttemptFailsTheJob) {
  JobStore s(db(), StoreOptions{10, 3});
  const int64_t j = s.submit(spec({1}, 1), 0);
  ASSERT_TRUE(s.lease("lost", 0));
  EXPECT_EQ(s.expire_leases(11), 1);
  EXPECT_EQ(s.job(j)->state, JobState::Failed);
  EXPECT_EQ(s.job(j)->finished_at, 11);
  EXPECT_EQ(s.tasks(j)[0].log, "lease expired (worker lost)");
}

TEST_F(JobLifecycleTest, ACanceledJobStaysCanceled) {
  JobStore s(db());
  const int64_t j = s.submit(spec({1, 2, 3}, 1), 0);
  const auto running = s.lease("w", 1);
  const auto failing = s.lease("w", 1);
  EXPECT_TRUE(s.fail(failing->lease_id, "crash", 2));
  EXPECT_TRUE(s.cancel(j, 5));
  EXPECT_EQ(s.job(j)->state, JobState::Canceled);
  EXPECT_EQ(s.job(j)->finished_at, 5);
  EXPECT_EQ(s.heartbeat(running->lease_id, 6), HeartbeatAnswer::Stop);
  EXPECT_EQ(s.retry_failed(j), 0);
  EXPECT_TRUE(s.resume(j));
  EXPECT_TRUE(s.pause(j));
  EXPECT_TRUE(s.cancel(j, 9));
  EXPECT_EQ(s.job(j)->state, JobState::Canceled);
  EXPECT_EQ(s.job(j)->finished_at, 5);
  EXPECT_FALSE(s.lease("w", 10));
}

TEST_F(JobLifecycleTest, APausedJobKeepsItsRunningTasksAndEndsWhenTheyDo) {
  JobStore s(db(), StoreOptions{10, 3});
  const int64_t j = s.submit(spec({1, 2}), 0);
  const auto a = s.lease("w", 1);
  const auto b = s.lease("w", 1);
  EXPECT_TRUE(s.pause(j));
  EXPECT_EQ(s.job(j)->state, JobState::Paused);
  EXPECT_EQ(s.job(j)->leased, 2);
  EXPECT_EQ(s.heartbeat(a->lease_id, 8), HeartbeatAnswer::KeepRunning);
  EXPECT_TRUE(s.complete(a->lease_id, "r1", 9));
  // b's worker is lost: its task is requeued as paused, not leased.
  EXPECT_EQ(s.expire_leases(12), 1);
  EXPECT_EQ(s.job(j)->paused, 1);
  EXPECT_FALSE(s.lease("w", 13));
  EXPECT_TRUE(s.resume(j));
  EXPECT_EQ(s.job(j)->state, JobState::Active);
  const auto again = s.lease("w", 14);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->task.id, b->task.id);
  EXPECT_EQ(again->task.attempts, 2);
  // Paused with only a leased task left: its completion ends the job.
  EXPECT_TRUE(s.pause(j));
  EXPECT_TRUE(s.complete(again->lease_id, "r2", 15));
  EXPECT_EQ(s.job(j)->state, JobState::Done);
  EXPECT_EQ(s.job(j)->finished_at, 15);
}

TEST_F(JobLifecycleTest, AResubmittedJobIsDoneAtSubmitFromTrustedRenderersResults) {
  JobStore s(db());
  s.submit(spec({1, 2}), 0);
  render_one(s, 1, "r1");
  render_one(s, 3, "r1");
  const int64_t busy = s.submit(
      [] {
        JobSpec b = spec({7});
        b.scene = "other";
        b.priority = 90;
        return b;
      }(),
      5);
  const int64_t again = s.submit(spec({1, 2}), 6);
  EXPECT_EQ(s.reuse_results(again, {"r2"}, 6), 0) << "another renderer's results";
  EXPECT_EQ(s.job(again)->state, JobState::Active);
  EXPECT_EQ(s.reuse_results(again, {"r2", "r1"}, 7), 2);
  const auto j = s.job(again);
  EXPECT_EQ(j->state, JobState::Done);
  EXPECT_EQ(j->started_at, 7);
  EXPECT_EQ(j->finished_at, 7);
  EXPECT_EQ(j->reused, 2);
  EXPECT_EQ(s.tasks(again)[0].attempts, 0) << "not rendered";
  EXPECT_EQ(s.frame(again, 2)->output, "r2");
  EXPECT_EQ(s.job(busy)->state, JobState::Active);
  EXPECT_EQ(s.reuse_results(busy, {"r1"}, 8), 0);
}

TEST_F(JobLifecycleTest, TheEtaFollowsThePaceOfRenderedTasks) {
  JobSummary j;
  j.state = JobState::Active;
  j.queued = 3;
  j.leased = 1;
  EXPECT_FALSE(estimate_eta(j, 100)) << "nothing rendered yet";
  j.started_at = 10;
  j.done = 4;
  j.reused = 2;                        // reused tasks took no time: not part of the pace
  EXPECT_EQ(estimate_eta(j, 30), 40);  // 2 rendered in 20 s, 4 left
  j.state = JobState::Paused;
  EXPECT_FALSE(estimate_eta(j, 30));
}

// A database of version 9 (before the lifecycle): its ended jobs end, and
// the leases its tasks had count as attempts.
TEST_F(JobLifecycleTest, Version9JobsThatEndedAreDoneOrFailedAfterTheMigration) {
  {
    sql::Db raw(db().string());
    raw.exec("CREATE TABLE schema_version(version INTEGER NOT NULL)");
    raw.exec("INSERT INTO schema_version(version) VALUES(9)");
    for (size_t v = 0; v < 9; ++v) raw.exec(schema_migrations()[v].sql);
    raw.exec(
        "INSERT INTO jobs(id, name, scene, spp, priority, max_attempts, state, created) VALUES"
        "(1, 'done', 's', 8, 50, 3, 'active', 0), (2, 'failed', 's', 8, 50, 3, 'active', 0), "
        "(3, 'running', 's', 8, 50, 3, 'active', 0), (4, 'canceled', 's', 8, 50, 3, 'canceled', "
        "0)");
    raw.exec(
        "INSERT INTO tasks(job_id, frame, sample_begin, sample_end, state, attempts) VALUES"
        "(1, 1, 0, 8, 'done', 0), (1, 2, 0, 8, 'done', 1), (2, 1, 0, 8, 'failed', 3), "
        "(2, 2, 0, 8, 'done', 0), (3, 1, 0, 8, 'done', 0), (3, 2, 0, 8, 'queued', 1), "
        "(4, 1, 0, 8, 'canceled', 0)");
  }
  JobStore s(db());
  EXPECT_EQ(s.job(1)->state, JobState::Done);
  EXPECT_FALSE(s.job(1)->finished_at) << "when it ended is not known";
  EXPECT_EQ(s.job(2)->state, JobState::Failed);
  EXPECT_EQ(s.job(3)->state, JobState::Active);
  EXPECT_EQ(s.job(4)->state, JobState::Canceled);
  EXPECT_EQ(s.tasks(1)[0].attempts, 1);
  EXPECT_EQ(s.tasks(1)[1].attempts, 2);
  EXPECT_EQ(s.tasks(3)[1].attempts, 1);
  // The queued task failed once before: two attempts are left of three.
  for (int i = 0; i < 2; ++i) {
    const auto l = s.lease("w", 1);
    ASSERT_TRUE(l);
    EXPECT_TRUE(s.fail(l->lease_id, "crash", 2));
  }
  EXPECT_EQ(s.job(3)->state, JobState::Failed);
}

}  // namespace
}  // namespace vesper
