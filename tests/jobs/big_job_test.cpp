// Big jobs (issue 17, item 9): a lease, a completion and a frame's status
// cost the same in a job of 20 tasks and of 20 000 — counted in SQLite
// virtual-machine steps, which are deterministic, not timed — the task list
// reads in pages in leasing order, and a read snapshot on a second
// connection neither blocks nor sees a writer's later changes.
#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>
#include <vector>

#include "jobs/job_store.h"
#include "jobs/sqlite_db.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {

JobSpec spec(std::vector<int> frames, int spp = 8, int split = 0) {
  return JobSpec{"job", "scene-sha", std::move(frames), spp, split, 50, 3, {}, {}, {}, {}, {}};
}

std::vector<int> frames_1_to(int n) {
  std::vector<int> f(size_t(n), 0);
  std::iota(f.begin(), f.end(), 1);
  return f;
}

// VM steps of one lease + complete, after `warmup` of them, by `worker` in a
// store holding one job of `tasks` one-frame tasks (and a worker that failed
// one task, so the blocklist and retry-elsewhere paths run too).
uint64_t steps_per_task(const fs::path& dir, int tasks) {
  JobStore s(dir / "jobs.sqlite");
  s.submit(spec(frames_1_to(tasks)), 0);
  const auto failed = s.lease("unlucky", 1);
  s.fail(failed->lease_id, "boom", 1);
  for (int i = 0; i < 5; ++i) s.complete(s.lease("w", 1)->lease_id, "r", 1);
  const uint64_t before = sql::vm_steps_on_this_thread();
  const auto lease = s.lease("w", 2);
  EXPECT_TRUE(lease);
  EXPECT_TRUE(s.complete(lease->lease_id, "r", 2));
  EXPECT_EQ(s.frames_awaiting_merge().size(), 0u);
  return sql::vm_steps_on_this_thread() - before;
}

TEST(BigJob, ALeaseCostsTheSameInAJobOf20And20000Tasks) {
  test::TempDir small("jobs"), big("jobs");
  const uint64_t few = steps_per_task(small.path(), 20);
  const uint64_t many = steps_per_task(big.path(), 20000);
  // A scan of every task would cost ≥ 20 000 steps more; the indexes keep
  // the difference to the few extra levels of a deeper B-tree.
  EXPECT_LT(double(many), 1.5 * double(few))
      << few << " VM steps for 20 tasks, " << many << " for 20 000";
  EXPECT_GT(few, 0u);
}

TEST(BigJob, TheTaskListReadsInPagesInLeasingOrder) {
  test::TempDir dir("jobs");
  JobStore s(dir.path() / "jobs.sqlite");
  const int64_t j = s.submit(spec({9, 1, 5}, 8, 4), 0);  // frames out of order, 2 ranges each
  const auto all = s.tasks(j);
  ASSERT_EQ(all.size(), 6u);
  for (size_t i = 1; i < all.size(); ++i) {
    EXPECT_LT(all[i - 1].id, all[i].id);
    EXPECT_LT(std::pair(all[i - 1].frame, all[i - 1].sample_begin),
              std::pair(all[i].frame, all[i].sample_begin));
  }
  std::vector<Task> paged;
  int pages = 0;
  for (int64_t after = 0;; ++pages) {
    const auto page = s.tasks(j, after, 4);
    if (page.empty()) break;
    EXPECT_LE(page.size(), 4u);
    paged.insert(paged.end(), page.begin(), page.end());
    after = page.back().id;
  }
  EXPECT_EQ(pages, 2);
  ASSERT_EQ(paged.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i) EXPECT_EQ(paged[i].id, all[i].id);
  // A page's frames: 5 … 9 holds frames 5 and 9, both with their two tasks.
  const auto frames = s.frames(j, 5, 9);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].frame, 5);
  EXPECT_EQ(frames[1].tasks, 2);
}

TEST(BigJob, AReadSnapshotSeesOneStateAndDoesNotBlockTheWriter) {
  test::TempDir dir("jobs");
  JobStore writer(dir.path() / "jobs.sqlite");
  JobStore reader(dir.path() / "jobs.sqlite");
  const int64_t j = writer.submit(spec({1, 2, 3}), 0);
  {
    JobStore::ReadSnapshot snapshot(reader);
    EXPECT_EQ(reader.job(j)->queued, 3);
    // The writer goes on while the snapshot lives (SQLITE_BUSY would throw)...
    const auto lease = writer.lease("w", 1);
    ASSERT_TRUE(lease);
    EXPECT_TRUE(writer.complete(lease->lease_id, "r", 1));
    EXPECT_GT(writer.submit(spec({4}), 1), j);
    // ...and the snapshot still sees the state it began with.
    EXPECT_EQ(reader.job(j)->queued, 3);
    EXPECT_EQ(reader.jobs().size(), 1u);
  }
  EXPECT_EQ(reader.job(j)->done, 1);
  EXPECT_EQ(reader.jobs().size(), 2u);
}

}  // namespace
}  // namespace vesper
