// JobStore housekeeping: deleting a job (refused while it has work queued or
// running; every row of it gone), the blobs jobs reference, blocklists.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "jobs/job_store.h"
#include "jobs/sqlite_db.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

class HousekeepingStoreTest : public ::testing::Test {
 protected:
  std::filesystem::path db() const { return dir_ / "jobs.sqlite"; }
  static JobSpec spec(const std::string& scene, std::vector<Asset> assets = {}) {
    return JobSpec{"job", scene, {1, 2}, 8, 0, 50, 3, std::move(assets), {}, {}, {}, {}};
  }
  // Rows left with this job's id.
  int64_t rows_of(int64_t job) {
    sql::Db d(db().string());
    int64_t n = 0;
    for (const char* table : {"tasks", "job_assets", "frame_outputs", "worker_task_failures"}) {
      const std::string q = std::string("SELECT COUNT(*) FROM ") + table + " WHERE job_id = ?1";
      sql::Stmt s(d, q.c_str());
      s.bind(1, job);
      if (s.step()) n += s.i64(0);
    }
    sql::Stmt s(d, "SELECT COUNT(*) FROM jobs WHERE id = ?1");
    s.bind(1, job);
    if (s.step()) n += s.i64(0);
    return n;
  }
  test::TempDir dir_{"housekeeping"};
};

TEST_F(HousekeepingStoreTest, ADeletedJobsIdIsNeverGivenAgain) {
  int64_t newest = 0;
  {
    JobStore s(db());
    s.submit(spec("a"), 0);
    newest = s.submit(spec("b"), 0);
    s.cancel(newest, 1);
    ASSERT_EQ(s.delete_job(newest), JobStore::DeleteResult::Deleted);
    EXPECT_GT(s.submit(spec("c"), 2), newest);  // SQLite alone would reuse it
    newest = s.jobs().back().id;
    s.cancel(newest, 3);
    ASSERT_EQ(s.delete_job(newest), JobStore::DeleteResult::Deleted);
  }
  JobStore reopened(db());  // the high-water mark is in the file
  EXPECT_GT(reopened.submit(spec("d"), 4), newest);
}

TEST_F(HousekeepingStoreTest, DeleteRefusesQueuedOrRunningWork) {
  JobStore s(db());
  const int64_t j = s.submit(spec("scene"), 0);
  JobSummary busy;
  EXPECT_EQ(s.delete_job(j, &busy), JobStore::DeleteResult::Busy);
  EXPECT_EQ(busy.queued, 2);
  auto l = s.lease("w", 1);
  ASSERT_TRUE(l);
  ASSERT_TRUE(s.complete(l->lease_id, "result-1", 2));
  l = s.lease("w", 3);
  ASSERT_TRUE(l);
  EXPECT_EQ(s.delete_job(j, &busy), JobStore::DeleteResult::Busy);
  EXPECT_EQ(busy.leased, 1);
  ASSERT_TRUE(s.fail(l->lease_id, "boom", 4));  // attempts left: queued again
  EXPECT_EQ(s.delete_job(j), JobStore::DeleteResult::Busy);
  s.cancel(j, 0);
  EXPECT_EQ(s.delete_job(j), JobStore::DeleteResult::Deleted);
  EXPECT_FALSE(s.job(j));
  EXPECT_EQ(rows_of(j), 0);
  EXPECT_EQ(s.delete_job(j), JobStore::DeleteResult::NotFound);
}

TEST_F(HousekeepingStoreTest, ReferencedBlobsAreScenesAssetsResultsAndOutputs) {
  JobStore s(db());
  const int64_t a = s.submit(spec("scene-a", {{"m.obj", "mesh"}}), 0);
  s.submit(spec("scene-b"), 0);
  auto l = s.lease("w", 1);
  ASSERT_TRUE(l);
  ASSERT_TRUE(s.complete(l->lease_id, "result-a1", 2));
  auto refs = s.referenced_blobs();
  std::sort(refs.begin(), refs.end());
  EXPECT_EQ(refs, (std::vector<std::string>{"mesh", "result-a1", "scene-a", "scene-b"}));
  s.cancel(a, 0);
  ASSERT_EQ(s.delete_job(a), JobStore::DeleteResult::Deleted);
  EXPECT_EQ(s.referenced_blobs(), std::vector<std::string>{"scene-b"});
}

TEST_F(HousekeepingStoreTest, BlocklistsByWorker) {
  JobStore s(db(), StoreOptions{60, 2});
  const int64_t j = s.submit(spec("scene"), 0);
  for (int i = 0; i < 2; ++i) {
    auto l = s.lease("bad", i);
    ASSERT_TRUE(l);
    ASSERT_TRUE(s.fail(l->lease_id, "boom", i));
  }
  EXPECT_EQ(s.blocklists(), (std::vector<std::pair<std::string, int64_t>>{{"bad", j}}));
  // Deleting the job forgets its blocklist.
  s.cancel(j, 0);
  ASSERT_EQ(s.delete_job(j), JobStore::DeleteResult::Deleted);
  EXPECT_TRUE(s.blocklists().empty());
}

}  // namespace
}  // namespace vesper
