// The job actions (cancel, pause, resume, retry-failed) and the job summary
// with its lifecycle: state, counts by task state, times (docs/farm.md, "Job
// lifecycle"). Part of JobStore (job_store.h).
#include <algorithm>
#include <initializer_list>
#include <optional>

#include "jobs/job_store.h"
#include "jobs/job_store_impl.h"

namespace vesper {
namespace {

// The state of job `job`, or nullopt for an unknown job.
std::optional<JobState> job_state(const sql::Db& db, int64_t job) {
  sql::Stmt s(db, "SELECT state FROM jobs WHERE id = ?1");
  s.bind(1, job);
  if (!s.step()) return std::nullopt;
  return parse_job_state(s.text(0));
}

// Moves job `job` from one of the states `from` to `to` (ending it at
// `finished`, when given) and runs `task_sql` (?1 = the job) on its tasks, in
// one transaction; false for an unknown job. A job in another state is left
// as it is.
bool change_job_state(sql::Db& db, int64_t job, std::initializer_list<JobState> from, JobState to,
                      const char* task_sql, std::optional<double> finished = std::nullopt) {
  sql::Transaction tx(db);
  const auto state = job_state(db, job);
  if (!state) return false;
  if (std::find(from.begin(), from.end(), *state) == from.end()) return true;
  sql::Stmt(db, "UPDATE jobs SET state = ?2, finished = COALESCE(?3, finished) WHERE id = ?1")
      .bind(1, job)
      .bind(2, std::string(to_string(to)))
      .bind(3, finished)
      .run();
  sql::Stmt(db, task_sql).bind(1, job).run();
  tx.commit();
  return true;
}

void count_task(JobSummary& j, TaskState state, int n) {
  switch (state) {
    case TaskState::Queued:
      j.queued = n;
      break;
    case TaskState::Leased:
      j.leased = n;
      break;
    case TaskState::Done:
      j.done = n;
      break;
    case TaskState::Failed:
      j.failed = n;
      break;
    case TaskState::Canceled:
      j.canceled = n;
      break;
    case TaskState::Paused:
      j.paused = n;
      break;
  }
}

}  // namespace

// Canceled tasks keep their lease id: the worker's next heartbeat on it
// answers Stop, and its late upload is refused.
bool JobStore::cancel(int64_t job, double now) {
  return change_job_state(impl_->db, job, {JobState::Active, JobState::Paused}, JobState::Canceled,
                          "UPDATE tasks SET state = 'canceled', lease_expiry = NULL "
                          "WHERE job_id = ?1 AND state IN ('queued', 'leased', 'paused')",
                          now);
}

// Leased tasks stay leased: their heartbeats keep them running and their
// results are taken; when the last one ends with nothing else to run, the
// paused job ends too (settle_job).
bool JobStore::pause(int64_t job) {
  return change_job_state(
      impl_->db, job, {JobState::Active}, JobState::Paused,
      "UPDATE tasks SET state = 'paused' WHERE job_id = ?1 AND state = 'queued'");
}

bool JobStore::resume(int64_t job) {
  return change_job_state(
      impl_->db, job, {JobState::Paused}, JobState::Active,
      "UPDATE tasks SET state = 'queued' WHERE job_id = ?1 AND state = 'paused'");
}

int JobStore::retry_failed(int64_t job) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const auto state = job_state(db, job);
  if (!state || *state == JobState::Canceled) return 0;
  sql::Stmt(db,
            "UPDATE tasks SET state = CASE WHEN ?2 = 'paused' THEN 'paused' ELSE 'queued' END, "
            "failures = 0 WHERE job_id = ?1 AND state = 'failed'")
      .bind(1, job)
      .bind(2, std::string(to_string(*state)))
      .run();
  const int n = sqlite3_changes(db.get());
  sql::Stmt(db, "DELETE FROM worker_task_failures WHERE job_id = ?1").bind(1, job).run();
  if (n > 0 && *state == JobState::Failed)
    sql::Stmt(db, "UPDATE jobs SET state = 'active', finished = NULL, announced = 0 WHERE id = ?1")
        .bind(1, job)
        .run();
  tx.commit();
  return n;
}

std::optional<JobSummary> JobStore::job(int64_t id) const {
  sql::Stmt s(impl_->db,
              "SELECT id, name, priority, state, created, started, finished FROM jobs "
              "WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  JobSummary j;
  j.id = s.i64(0);
  j.name = s.text(1);
  j.priority = int(s.i64(2));
  j.state = parse_job_state(s.text(3));
  j.submitted_at = s.f64(4);
  j.started_at = s.optional_f64(5);
  j.finished_at = s.optional_f64(6);
  sql::Stmt c(impl_->db,
              "SELECT state, COUNT(*), COUNT(reused_from) FROM tasks WHERE job_id = ?1 "
              "GROUP BY state");
  c.bind(1, id);
  while (c.step()) {
    const TaskState state = parse_task_state(c.text(0));
    count_task(j, state, int(c.i64(1)));
    if (state == TaskState::Done) j.reused = int(c.i64(2));
  }
  return j;
}

std::vector<JobSummary> JobStore::jobs() const {
  std::vector<int64_t> ids;
  {
    sql::Stmt s(impl_->db, "SELECT id FROM jobs ORDER BY id");
    while (s.step()) ids.push_back(s.i64(0));
  }
  std::vector<JobSummary> out;
  for (int64_t id : ids) out.push_back(*job(id));
  return out;
}

std::vector<JobStore::EndedJob> JobStore::jobs_to_announce() const {
  std::vector<int64_t> ids;
  {
    sql::Stmt s(impl_->db,
                "SELECT id FROM jobs WHERE announced = 0 AND state IN ('done', 'failed', "
                "'canceled') ORDER BY id");
    while (s.step()) ids.push_back(s.i64(0));
  }
  std::vector<EndedJob> out;
  for (const int64_t id : ids) {
    sql::Stmt frames(impl_->db, "SELECT COUNT(DISTINCT frame) FROM tasks WHERE job_id = ?1");
    frames.bind(1, id);
    frames.step();
    out.push_back({*job(id), int(frames.i64(0))});
  }
  return out;
}

void JobStore::mark_announced(int64_t job) {
  sql::Transaction tx(impl_->db);
  sql::Stmt(impl_->db, "UPDATE jobs SET announced = 1 WHERE id = ?1").bind(1, job).run();
  tx.commit();
}

void JobStore::mark_all_announced() {
  sql::Transaction tx(impl_->db);
  impl_->db.exec(
      "UPDATE jobs SET announced = 1 WHERE announced = 0 AND state IN ('done', 'failed', "
      "'canceled')");
  tx.commit();
}

}  // namespace vesper
