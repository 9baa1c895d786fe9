#include "jobs/result_reuse.h"

#include <algorithm>
#include <vector>

#include "jobs/job_store_impl.h"

namespace vesper {

std::string inputs_key(const JobSpec& spec) {
  std::vector<std::string> assets;
  for (const Asset& a : spec.assets) assets.push_back(a.name + "=" + a.blob);
  std::sort(assets.begin(), assets.end());
  // With frame states, the scene and its assets are in each task's state:
  // the jobs of two versions of a scene share a key, their tasks match by state.
  const bool by_frame = !spec.frame_states.empty();
  std::string key = (by_frame ? "frame-state" : spec.scene) + ";spp=" + std::to_string(spec.spp);
  // Only what is set, so a job without a budget keeps the key it always had.
  const RenderBudget& b = spec.budget;
  if (b.noise_target) key += ";noise_target=" + exact_text(*b.noise_target);
  if (b.min_spp) key += ";min_spp=" + std::to_string(*b.min_spp);
  if (b.time_limit) key += ";time_limit=" + exact_text(*b.time_limit);
  key += overrides_key(spec.overrides);
  if (!by_frame)
    for (const auto& a : assets) key += ";" + a;
  return key;
}

bool complete_from_identical_task(JobStore::Impl& store, int64_t task_id,
                                  const std::string& renderer, double now) {
  if (renderer.empty()) return false;
  sql::Stmt same(
      store.db,
      "SELECT d.id, d.result FROM tasks t JOIN jobs j ON j.id = t.job_id "
      "JOIN tasks d ON d.state = 'done' AND d.frame = t.frame AND "
      "d.sample_begin = t.sample_begin AND d.sample_end = t.sample_end AND "
      "d.renderer = ?2 AND d.result <> '' AND d.id <> t.id AND d.frame_state = t.frame_state "
      "JOIN jobs dj ON dj.id = d.job_id AND dj.inputs_key = j.inputs_key "
      "WHERE t.id = ?1 AND j.inputs_key <> '' ORDER BY d.id LIMIT 1");
  same.bind(1, task_id).bind(2, renderer);
  if (!same.step()) return false;
  const int64_t source = same.i64(0);
  const std::string result = same.text(1);
  sql::Stmt(store.db,
            "UPDATE tasks SET state = 'done', result = ?2, renderer = ?3, reused_from = ?4, "
            "started = ?5, finished = ?5 WHERE id = ?1")
      .bind(1, task_id)
      .bind(2, result)
      .bind(3, renderer)
      .bind(4, source)
      .bind(5, now)
      .run();
  const Task task = *store.task(task_id);
  store.record_output_if_single_task_frame(task, result, now);
  store.mark_job_started(task.job_id, now);
  store.settle_job(task.job_id, now);
  return true;
}

namespace {
// Whether another job with the inputs of `job` has a task done by a known
// renderer: without one, nothing of `job` can be reused (one query, not one per task).
bool may_reuse(const sql::Db& db, int64_t job) {
  sql::Stmt s(db,
              "SELECT 1 FROM jobs j JOIN jobs o ON o.inputs_key = j.inputs_key AND o.id <> j.id "
              "WHERE j.id = ?1 AND j.inputs_key <> '' AND EXISTS(SELECT 1 FROM tasks d WHERE "
              "d.state = 'done' AND d.job_id = o.id AND d.renderer <> '') LIMIT 1");
  s.bind(1, job);
  return s.step();
}
}  // namespace

int JobStore::reuse_results(int64_t job, const std::vector<std::string>& renderers, double now) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  if (renderers.empty() || !may_reuse(db, job)) return 0;
  std::vector<int64_t> queued;
  {
    sql::Stmt s(db, "SELECT id FROM tasks WHERE job_id = ?1 AND state = 'queued' ORDER BY id");
    s.bind(1, job);
    while (s.step()) queued.push_back(s.i64(0));
  }
  int reused = 0;
  for (const int64_t task : queued)
    for (const std::string& renderer : renderers)
      if (complete_from_identical_task(*impl_, task, renderer, now)) {
        ++reused;
        break;
      }
  tx.commit();
  return reused;
}

}  // namespace vesper
