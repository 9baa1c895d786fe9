#include "jobs/job_store_impl.h"

#include <tuple>

namespace vesper {

TaskState parse_task_state(const std::string& s) {
  for (TaskState t : {TaskState::Queued, TaskState::Leased, TaskState::Done, TaskState::Failed,
                      TaskState::Canceled, TaskState::Paused})
    if (s == to_string(t)) return t;
  throw StoreError("unknown task state '" + s + "' in the store");
}

JobState parse_job_state(const std::string& s) {
  for (JobState j :
       {JobState::Active, JobState::Paused, JobState::Done, JobState::Failed, JobState::Canceled})
    if (s == to_string(j)) return j;
  throw StoreError("unknown job state '" + s + "' in the store");
}

Task read_task(const sql::Stmt& s) {
  Task t;
  t.id = s.i64(0);
  t.job_id = s.i64(1);
  t.frame = int(s.i64(2));
  t.sample_begin = int(s.i64(3));
  t.sample_end = int(s.i64(4));
  t.state = parse_task_state(s.text(5));
  t.attempts = int(s.i64(6));
  t.worker = s.text(7);
  t.result = s.text(8);
  t.log = s.text(9);
  t.reused_from = s.i64(10);  // NULL reads as 0
  t.started = s.optional_f64(11);
  t.finished = s.optional_f64(12);
  return t;
}

int JobStore::Impl::version() const {
  sql::Stmt s(db, "SELECT version FROM schema_version");
  return s.step() ? int(s.i64(0)) : 0;
}

std::optional<Task> JobStore::Impl::task(int64_t id) const {
  sql::Stmt s(db, (std::string("SELECT ") + kTaskColumns + " FROM tasks WHERE id = ?1").c_str());
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_task(s);
}

std::optional<Task> JobStore::Impl::leased_task(const std::string& lease_id) const {
  sql::Stmt s(db, (std::string("SELECT ") + kTaskColumns +
                   " FROM tasks WHERE lease_id = ?1 AND state = 'leased'")
                      .c_str());
  s.bind(1, lease_id);
  if (!s.step()) return std::nullopt;
  return read_task(s);
}

std::vector<Asset> JobStore::Impl::assets(int64_t job) const {
  sql::Stmt s(db, "SELECT name, blob FROM job_assets WHERE job_id = ?1 ORDER BY ord");
  s.bind(1, job);
  std::vector<Asset> out;
  while (s.step()) out.push_back({s.text(0), s.text(1)});
  return out;
}

std::vector<FrameStatus> JobStore::Impl::frames(int64_t job, int first, int last) const {
  // A range the (job_id, frame, sample_begin) index answers: one frame, asked
  // at every completion, costs the same in a job of 10 or 100 000 tasks.
  sql::Stmt s(db,
              "SELECT t.frame, t.state, t.result, o.blob, o.noise_read, o.noise_reached, "
              "o.spp_mean, o.stop_reason FROM tasks t LEFT JOIN frame_outputs o "
              "ON o.job_id = t.job_id AND o.frame = t.frame WHERE t.job_id = ?1 AND t.frame "
              "BETWEEN ?2 AND ?3 ORDER BY t.frame, t.sample_begin");
  s.bind(1, job).bind(2, int64_t(first)).bind(3, int64_t(last));
  std::vector<FrameStatus> out;
  while (s.step()) {
    const int frame = int(s.i64(0));
    if (out.empty() || out.back().frame != frame) {
      out.emplace_back();
      out.back().frame = frame;
      out.back().output = s.text(3);
      if (s.i64(4) != 0)
        out.back().noise = FrameNoise{s.optional_f64(5), s.optional_f64(6), s.text(7)};
    }
    FrameStatus& f = out.back();
    ++f.tasks;
    switch (parse_task_state(s.text(1))) {
      case TaskState::Done:
        ++f.done;
        f.results.push_back(s.text(2));
        break;
      case TaskState::Failed:
        ++f.failed;
        break;
      case TaskState::Canceled:
        ++f.canceled;
        break;
      default:
        break;
    }
  }
  return out;
}

std::string JobStore::Impl::record_output(int64_t job, int frame, const std::string& blob,
                                          double now) {
  // An output already read for another frame (a reused result) brings its noise along.
  sql::Stmt(db,
            "INSERT INTO frame_outputs(job_id, frame, blob, created, noise_read, noise_reached, "
            "spp_mean, stop_reason) SELECT ?1, ?2, ?3, ?4, COALESCE(r.noise_read, 0), "
            "r.noise_reached, r.spp_mean, r.stop_reason FROM (SELECT 1) LEFT JOIN (SELECT * FROM "
            "frame_outputs WHERE blob = ?3 AND noise_read = 1 LIMIT 1) r ON 1 WHERE 1 "
            "ON CONFLICT(job_id, frame) DO NOTHING")
      .bind(1, job)
      .bind(2, int64_t(frame))
      .bind(3, blob)
      .bind(4, now)
      .run();
  sql::Stmt s(db, "SELECT blob FROM frame_outputs WHERE job_id = ?1 AND frame = ?2");
  s.bind(1, job).bind(2, int64_t(frame));
  return s.step() ? s.text(0) : std::string();
}

void JobStore::Impl::record_output_if_single_task_frame(const Task& task, const std::string& result,
                                                        double now,
                                                        const std::optional<FrameNoise>& noise) {
  const auto frame = frames(task.job_id, task.frame, task.frame);
  if (frame.size() != 1 || frame[0].tasks != 1 || !frame[0].complete()) return;
  record_output(task.job_id, task.frame, result, now);
  if (noise) record_noise(task.job_id, task.frame, *noise);
}

void JobStore::Impl::record_noise(int64_t job, int frame, const FrameNoise& noise) {
  sql::Stmt(db,
            "UPDATE frame_outputs SET noise_read = 1, noise_reached = ?3, spp_mean = ?4, "
            "stop_reason = ?5 WHERE job_id = ?1 AND frame = ?2 AND noise_read = 0")
      .bind(1, job)
      .bind(2, int64_t(frame))
      .bind(3, noise.noise_reached)
      .bind(4, noise.spp_mean)
      .bind(5, noise.stop_reason)
      .run();
}

void JobStore::Impl::record_failure(int64_t task_id, int64_t job_id, const std::string& worker,
                                    const std::string& log, double now) {
  sql::Stmt(db,
            "UPDATE tasks SET failures = failures + 1, lease_id = NULL, lease_expiry = NULL, "
            "log = ?2, finished = ?3, state = CASE WHEN failures + 1 >= (SELECT max_attempts "
            "FROM jobs WHERE id = job_id) THEN 'failed' WHEN (SELECT state FROM jobs WHERE id = "
            "job_id) = 'paused' THEN 'paused' ELSE 'queued' END WHERE id = ?1")
      .bind(1, task_id)
      .bind(2, log)
      .bind(3, now)
      .run();
  if (!worker.empty())
    sql::Stmt(db,
              "INSERT INTO worker_task_failures(job_id, worker, task_id, failures) "
              "VALUES(?1, ?2, ?3, 1) ON CONFLICT(job_id, worker, task_id) "
              "DO UPDATE SET failures = failures + 1")
        .bind(1, job_id)
        .bind(2, worker)
        .bind(3, task_id)
        .run();
  settle_job(job_id, now);
}

void JobStore::Impl::mark_job_started(int64_t job, double now) {
  sql::Stmt(db, "UPDATE jobs SET started = ?2 WHERE id = ?1 AND started IS NULL")
      .bind(1, job)
      .bind(2, now)
      .run();
}

void JobStore::Impl::settle_job(int64_t job, double now) {
  // Through tasks_by_state (state, job_id): a probe per state, whatever the job's size.
  sql::Stmt(db,
            "UPDATE jobs SET finished = ?2, state = CASE WHEN EXISTS(SELECT 1 FROM tasks WHERE "
            "state = 'failed' AND job_id = ?1) THEN 'failed' WHEN EXISTS(SELECT 1 FROM tasks "
            "WHERE state = 'canceled' AND job_id = ?1) THEN 'canceled' ELSE 'done' END "
            "WHERE id = ?1 AND state IN ('active', 'paused') AND NOT EXISTS(SELECT 1 FROM tasks "
            "WHERE state IN ('queued', 'leased', 'paused') AND job_id = ?1)")
      .bind(1, job)
      .bind(2, now)
      .run();
}

int JobStore::Impl::expire(double now) {
  std::vector<std::tuple<int64_t, int64_t, std::string>> expired;
  {
    sql::Stmt s(
        db, "SELECT id, job_id, worker FROM tasks WHERE state = 'leased' AND lease_expiry < ?1");
    s.bind(1, now);
    while (s.step()) expired.emplace_back(s.i64(0), s.i64(1), s.text(2));
  }
  for (const auto& [id, job, worker] : expired)
    record_failure(id, job, worker, "lease expired (worker lost)", now);
  return int(expired.size());
}

}  // namespace vesper
