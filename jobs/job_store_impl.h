#pragma once
// JobStore's internals, shared by the files that implement it (job_store.cpp,
// scheduling.cpp, result_reuse.cpp): the database, the options, and the
// queries several operations need. Not part of the public API.
#include <optional>
#include <string>
#include <vector>

#include "jobs/job_store.h"
#include "jobs/sqlite_db.h"

namespace vesper {

TaskState parse_task_state(const std::string& s);
JobState parse_job_state(const std::string& s);

// The columns read_task() reads, in its order: "SELECT <kTaskColumns> FROM tasks ...".
inline constexpr const char* kTaskColumns =
    "id, job_id, frame, sample_begin, sample_end, state, attempts, worker, result, log, "
    "reused_from, started, finished";
Task read_task(const sql::Stmt& s);

struct JobStore::Impl {
  sql::Db db;
  StoreOptions options;
  Impl(const std::filesystem::path& file, StoreOptions o) : db(file.string()), options(o) {}

  int version() const;
  std::optional<Task> task(int64_t id) const;
  // The current task of a lease id, if the lease is still current.
  std::optional<Task> leased_task(const std::string& lease_id) const;
  std::vector<Asset> assets(int64_t job) const;
  // A job's frames numbered first … last, ascending.
  std::vector<FrameStatus> frames(int64_t job, int first, int last) const;

  // Records a frame's output unless one is recorded already; returns the recorded blob.
  std::string record_output(int64_t job, int frame, const std::string& blob, double now);
  // A frame of one task: its result, just committed, is the frame's output
  // (with `noise`, when given, as what the output says of its noise).
  void record_output_if_single_task_frame(const Task& task, const std::string& result, double now,
                                          const std::optional<FrameNoise>& noise = std::nullopt);
  // Records a frame output's noise unless it was read already.
  void record_noise(int64_t job, int frame, const FrameNoise& noise);

  // Failed attempt bookkeeping shared by fail() and lease expiry: the task
  // is requeued (paused, in a paused job) or, out of attempts, failed.
  void record_failure(int64_t task_id, int64_t job_id, const std::string& worker,
                      const std::string& log, double now);
  // A task of `job` was leased or reused at `now`: the job started, if it had not.
  void mark_job_started(int64_t job, double now);
  // A task of `job` ended: when nothing is left to run, the job ends done
  // (every task done) or failed (one failed), at `now`. Canceled jobs stay
  // canceled. Cheap when tasks are left (an index probe), so it follows
  // every task that ends.
  void settle_job(int64_t job, double now);
  // Requeues the tasks whose lease expired before `now`; returns how many.
  int expire(double now);
};

}  // namespace vesper
