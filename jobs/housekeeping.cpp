// JobStore's housekeeping: deleting a job, the blobs jobs reference, the
// workers' blocklists.
#include <string>
#include <vector>

#include "jobs/job_store_impl.h"

namespace vesper {
namespace {

// Tables (other than `except`) with a column named `column`: a job's rows are
// found by their job_id or task_id wherever a migration put them, so a
// migration adding a table keyed by either needs no change here.
std::vector<std::string> tables_with(sql::Db& db, const std::string& column,
                                     const std::string& except) {
  std::vector<std::string> out;
  sql::Stmt s(db,
              "SELECT m.name FROM sqlite_master m, pragma_table_info(m.name) c "
              "WHERE m.type = 'table' AND c.name = ?1 AND m.name != ?2 ORDER BY m.name");
  s.bind(1, column).bind(2, except);
  while (s.step()) out.push_back(s.text(0));
  return out;
}

void delete_rows(sql::Db& db, const std::string& table, const std::string& where, int64_t id) {
  const std::string sql = "DELETE FROM \"" + table + "\" WHERE " + where;
  sql::Stmt(db, sql.c_str()).bind(1, id).run();
}

}  // namespace

JobStore::DeleteResult JobStore::delete_job(int64_t id, JobSummary* busy) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const std::optional<JobSummary> j = job(id);
  if (!j) return DeleteResult::NotFound;
  if (j->queued + j->leased > 0) {
    if (busy) *busy = *j;
    return DeleteResult::Busy;
  }
  // Children first (foreign keys are on): rows of its tasks, of the job, then the job.
  for (const std::string& t : tables_with(db, "task_id", "tasks"))
    delete_rows(db, t, "task_id IN (SELECT id FROM tasks WHERE job_id = ?1)", id);
  for (const std::string& t : tables_with(db, "job_id", "tasks"))
    delete_rows(db, t, "job_id = ?1", id);
  sql::Stmt(db, "DELETE FROM tasks WHERE job_id = ?1").bind(1, id).run();
  sql::Stmt(db, "DELETE FROM jobs WHERE id = ?1").bind(1, id).run();
  tx.commit();
  return DeleteResult::Deleted;
}

std::vector<std::string> JobStore::referenced_blobs() const {
  sql::Stmt s(
      impl_->db,
      "SELECT scene FROM jobs UNION SELECT blob FROM job_assets "
      "UNION SELECT result FROM tasks WHERE result != '' UNION SELECT blob FROM frame_outputs");
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.text(0));
  return out;
}

std::vector<std::pair<std::string, int64_t>> JobStore::blocklists() const {
  sql::Stmt s(impl_->db,
              "SELECT worker, job_id FROM worker_task_failures GROUP BY worker, job_id "
              "HAVING COUNT(*) >= ?1 ORDER BY worker, job_id");
  s.bind(1, int64_t(impl_->options.blocklist_threshold));
  std::vector<std::pair<std::string, int64_t>> out;
  while (s.step()) out.emplace_back(s.text(0), s.i64(1));
  return out;
}

}  // namespace vesper
