#pragma once
// The job store: SQLite in WAL mode with schema migrations. Every state
// change is one IMMEDIATE transaction, so a process killed at any moment
// leaves either the old or the new state, never a mix. Time is passed in by
// the caller (seconds), which keeps lease expiry testable.
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "jobs/job.h"

namespace vesper {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StoreOptions {
  double lease_seconds = 60;
  int blocklist_threshold =
      3;  // distinct tasks of a job a worker failed before it is blocked for that job
};

// KeepRunning extends the lease (a paused job's leased tasks keep running);
// Stop: the job was canceled;
// StaleLease: the lease expired or was replaced (the worker lost the task).
enum class HeartbeatAnswer { KeepRunning, Stop, StaleLease };

class JobStore {
 public:
  // Opens (creating if needed) and migrates the database.
  explicit JobStore(const std::filesystem::path& file, StoreOptions options = {});
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  int schema_version() const;

  int64_t submit(const JobSpec& spec, double now);
  // Requeues expired leases, then leases the best queued task this worker is
  // not blocked for (highest priority, oldest job, tasks this worker has not
  // failed before those it has, lowest frame first).
  //
  // Identical tasks are rendered once: a queued task whose inputs (scene blob,
  // spp, assets), frame and sample range equal those of a task already done by
  // the same `renderer` (an opaque id, e.g. the renderer executable's sha256;
  // empty = never reuse) is completed with that result instead of being
  // leased (`reused`, if given, counts them), and the next task is looked at.
  std::optional<Lease> lease(const std::string& worker, double now,
                             const std::string& renderer = "", int* reused = nullptr);
  // The lease `lease_id` while it is current (expiry not filled in), as
  // lease() granted it: what the server checks a result against. nullopt
  // for a stale lease.
  std::optional<Lease> current_lease(const std::string& lease_id) const;
  HeartbeatAnswer heartbeat(const std::string& lease_id, double now);
  // Both refuse (return false) a lease that is no longer current: expired,
  // re-leased, canceled. Committed results are never touched by stale calls.
  // `result_noise`, when given, is what the result says of its noise: a
  // one-task frame's output is recorded with it, in the same transaction.
  // `log_tail`: the tail of the render's log (kept as the task's log).
  bool complete(const std::string& lease_id, const std::string& result, double now,
                const std::optional<FrameNoise>& result_noise = std::nullopt,
                const std::string& log_tail = {});
  bool fail(const std::string& lease_id, const std::string& log_tail, double now);
  // Requeues tasks whose lease expired (counted as a failed attempt).
  int expire_leases(double now);
  // Gives every live lease at least lease_seconds from `now`; returns how
  // many. A server calls it when it starts: while it was down no worker could
  // heartbeat, so a lease must not be lost (and charged to its task and
  // worker) for the server's absence.
  int renew_leases(double now);

  // Job actions (docs/farm.md, "Job lifecycle"); false / 0 for an unknown
  // job. Cancel ends an active or paused job at `now` (its leased tasks are
  // told to stop at their next heartbeat); a job that ended stays as it is.
  // Pause stops leasing the job's tasks, and its leased tasks run on (their
  // results are taken); resume undoes it. retry_failed requeues the failed
  // tasks of a job that is not canceled, and a failed job is active again.
  bool cancel(int64_t job, double now);
  bool pause(int64_t job);
  bool resume(int64_t job);
  int retry_failed(int64_t job);
  // Completes the queued tasks of `job` whose identical task (result_reuse.h)
  // is done by one of `renderers` (the builds trusted for reuse) with its
  // result, at `now`; returns how many. Called at submit, so a job whose
  // tasks were all rendered before ends at once instead of waiting for a
  // lease to reach it. Costs one query when no job with the same inputs has
  // a done task.
  int reuse_results(int64_t job, const std::vector<std::string>& renderers, double now);

  // Jobs that ended (done, failed, canceled) and were not announced yet
  // (server/job_webhook.h), oldest first; `frames` each one's frame count.
  struct EndedJob {
    JobSummary job;
    int frames = 0;
  };
  std::vector<EndedJob> jobs_to_announce() const;
  // The job was announced (or, with no webhook, need not be); a job that
  // ends again after a retry is announced again.
  void mark_announced(int64_t job);
  void mark_all_announced();

  std::optional<JobSummary> job(int64_t job) const;
  std::vector<JobSummary> jobs() const;
  // The job's tasks in leasing order (frame, then sample range), which is id
  // order: those with an id above `after`, at most `limit` of them (a page of
  // a big job's task list; 0 = no limit).
  std::vector<Task> tasks(int64_t job, int64_t after = 0, size_t limit = 0) const;
  bool blocked(int64_t job, const std::string& worker) const;
  std::vector<std::string> blocked_workers(int64_t job) const;
  std::vector<Asset> assets(int64_t job) const;

  // Frames of a job (ascending), with their tasks' results and recorded
  // output: all, or those numbered first … last (a page of the task list's).
  std::vector<FrameStatus> frames(int64_t job) const;
  std::vector<FrameStatus> frames(int64_t job, int first, int last) const;
  std::optional<FrameStatus> frame(int64_t job, int frame) const;
  // Records `blob` as the output of a finished frame, once: when an output is
  // recorded already (another merge won the race) it is kept. Returns the
  // recorded blob. A frame of one task gets its output from complete(), in
  // the same transaction. With `noise`, the output's noise is recorded in
  // that transaction too (as record_frame_noise): readers on another
  // connection never see the frame ready without it. Throws StoreError if
  // the frame is not finished.
  std::string record_frame_output(int64_t job, int frame, const std::string& blob, double now,
                                  const std::optional<FrameNoise>& noise = std::nullopt);
  // (job, frame) of every finished frame of several tasks that has no output
  // recorded yet: the frames that wait for a merge.
  std::vector<std::pair<int64_t, int>> frames_awaiting_merge() const;

  // Frame outputs whose noise (FrameNoise, in the output's metadata) has not
  // been read yet, by job and frame. An output recorded with a blob another
  // frame's read output has (a reused result) takes its noise at once.
  struct UnreadOutput {
    int64_t job = 0;
    int frame = 0;
    std::string blob;
  };
  std::vector<UnreadOutput> outputs_without_noise() const;
  // Records what a frame's output says of its noise, once (a second record
  // changes nothing). Throws StoreError if the frame has no output.
  void record_frame_noise(int64_t job, int frame, const FrameNoise& noise);

  // Housekeeping (housekeeping.cpp). Deletes a job that has no task queued
  // or leased, with every row that belongs to it (or to its tasks) in any
  // table. Deleted: true; NotFound: no such job; Busy: it has work queued or
  // running (`busy`, if given, gets its summary).
  enum class DeleteResult { Deleted, NotFound, Busy };
  DeleteResult delete_job(int64_t job, JobSummary* busy = nullptr);
  // Every blob a job references: scenes, assets, task results, frame outputs.
  std::vector<std::string> referenced_blobs() const;
  // (worker id, job) for each job a worker is blocked for, by worker then job.
  std::vector<std::pair<std::string, int64_t>> blocklists() const;

  // While one lives, every read of this JobStore sees one consistent state
  // (a read transaction; in WAL mode writers on other connections go on).
  // For a second, read-only JobStore on the same file: the server answers
  // reads from one without holding the writers' lock (server/locked_store.h).
  class ReadSnapshot {
   public:
    explicit ReadSnapshot(JobStore& store);
    ~ReadSnapshot();
    ReadSnapshot(const ReadSnapshot&) = delete;
    ReadSnapshot& operator=(const ReadSnapshot&) = delete;

   private:
    JobStore& store_;
  };

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace vesper
