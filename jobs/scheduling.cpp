#include "jobs/scheduling.h"

#include "jobs/sqlite_db.h"

namespace vesper {

std::optional<int64_t> next_task(const sql::Db& db, const std::string& worker,
                                 int blocklist_threshold) {
  sql::Stmt pick(db,
                 "SELECT t.id FROM tasks t JOIN jobs j ON j.id = t.job_id "
                 "WHERE t.state = 'queued' AND j.state = 'active' AND ("
                 "  SELECT COUNT(*) FROM worker_task_failures f WHERE f.job_id = j.id AND "
                 "f.worker = ?1) < ?2 "
                 "ORDER BY j.priority DESC, j.id, EXISTS(SELECT 1 FROM worker_task_failures g "
                 "WHERE g.task_id = t.id AND g.worker = ?1), t.frame, t.sample_begin LIMIT 1");
  pick.bind(1, worker).bind(2, int64_t(blocklist_threshold));
  if (!pick.step()) return std::nullopt;
  return pick.i64(0);
}

}  // namespace vesper
