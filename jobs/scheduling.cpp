#include "jobs/scheduling.h"

#include "jobs/sqlite_db.h"

namespace vesper {

// Two short queries instead of one sorted scan of every queued task: the job
// first (a handful of rows, each checked through the queued-task index), then
// the first task in leasing order within it (the index's order, so the scan
// stops at the first row; a worker skips at most the few tasks it failed
// before being blocked). A lease costs the same for a job of 10 tasks and one
// of 100 000 (bench/farm/big_job.cpp).
std::optional<int64_t> next_task(const sql::Db& db, const std::string& worker,
                                 int blocklist_threshold) {
  sql::Stmt job(db,
                "SELECT j.id FROM jobs j WHERE j.state = 'active' AND EXISTS(SELECT 1 FROM tasks "
                "t WHERE t.job_id = j.id AND t.state = 'queued') AND (SELECT COUNT(*) FROM "
                "worker_task_failures f WHERE f.job_id = j.id AND f.worker = ?1) < ?2 "
                "ORDER BY j.priority DESC, j.id LIMIT 1");
  job.bind(1, worker).bind(2, int64_t(blocklist_threshold));
  if (!job.step()) return std::nullopt;
  const int64_t job_id = job.i64(0);
  // Tasks this worker has not failed first: a retry goes elsewhere when it can.
  sql::Stmt fresh(db,
                  "SELECT t.id FROM tasks t WHERE t.job_id = ?1 AND t.state = 'queued' AND NOT "
                  "EXISTS(SELECT 1 FROM worker_task_failures g WHERE g.job_id = ?1 AND g.worker = "
                  "?2 AND g.task_id = t.id) ORDER BY t.frame, t.sample_begin LIMIT 1");
  fresh.bind(1, job_id).bind(2, worker);
  if (fresh.step()) return fresh.i64(0);
  sql::Stmt any(db,
                "SELECT t.id FROM tasks t WHERE t.job_id = ?1 AND t.state = 'queued' "
                "ORDER BY t.frame, t.sample_begin LIMIT 1");
  any.bind(1, job_id);
  if (any.step()) return any.i64(0);
  return std::nullopt;
}

}  // namespace vesper
