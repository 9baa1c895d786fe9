#include "jobs/job_store.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <random>

#include "jobs/job_store_impl.h"
#include "jobs/migrations.h"
#include "jobs/result_reuse.h"
#include "jobs/scheduling.h"

namespace vesper {

void describe_lease(const JobStore::Impl& store, Lease& lease);

namespace {

std::string new_lease_id() {
  thread_local std::mt19937_64 rng{std::random_device{}()};
  static const char* hex = "0123456789abcdef";
  std::string id(32, '0');
  for (int half = 0; half < 2; ++half) {
    uint64_t v = rng();
    for (int i = 0; i < 16; ++i, v >>= 4) id[size_t(half * 16 + i)] = hex[v & 15];
  }
  return id;
}

// Leases queued task `task_id` to `worker` until now + lease_seconds, under a new lease id.
Lease grant_lease(JobStore::Impl& store, int64_t task_id, const std::string& worker,
                  const std::string& renderer, double now) {
  Lease lease;
  lease.lease_id = new_lease_id();
  lease.expiry = now + store.options.lease_seconds;
  sql::Stmt(store.db,
            "UPDATE tasks SET state = 'leased', lease_id = ?2, worker = ?3, lease_expiry = ?4, "
            "renderer = ?5, attempts = attempts + 1, started = ?6, finished = NULL WHERE id = ?1")
      .bind(1, task_id)
      .bind(2, lease.lease_id)
      .bind(3, worker)
      .bind(4, lease.expiry)
      .bind(5, renderer)
      .bind(6, now)
      .run();
  lease.task = *store.leased_task(lease.lease_id);
  store.mark_job_started(lease.task.job_id, now);
  describe_lease(store, lease);
  return lease;
}

}  // namespace

// What the worker of `lease.task` is to render: the job's scene, spp, this
// task's budget, overrides and assets.
void describe_lease(const JobStore::Impl& store, Lease& lease) {
  sql::Stmt job(store.db,
                "SELECT scene, spp, noise_target, min_spp, time_limit, aovs, layer_variance, seed, "
                "scale, task_timeout, half FROM jobs WHERE id = ?1");
  job.bind(1, lease.task.job_id);
  job.step();
  lease.scene = job.text(0);
  lease.spp = int(job.i64(1));
  RenderBudget frame;
  frame.noise_target = job.optional_f64(2);
  if (const auto min_spp = job.optional_i64(3)) frame.min_spp = int(*min_spp);
  frame.time_limit = job.optional_f64(4);
  lease.budget = task_budget(frame, lease.spp, lease.task.sample_begin, lease.task.sample_end);
  RenderOverrides& o = lease.overrides;
  o.aovs = split_aovs(job.text(5));
  o.layer_variance = job.i64(6) != 0;
  if (const auto seed = job.optional_i64(7)) o.seed = uint64_t(*seed);
  o.scale = job.optional_f64(8);
  lease.task_timeout = job.optional_f64(9);
  o.half = job.i64(10) != 0;
  lease.assets = store.assets(lease.task.job_id);
}

JobStore::JobStore(const std::filesystem::path& file, StoreOptions options)
    : impl_(std::make_unique<Impl>(file, options)) {
  auto& db = impl_->db;
  db.exec("PRAGMA journal_mode = WAL");
  db.exec("PRAGMA synchronous = FULL");  // a committed state change survives power loss
  db.exec("PRAGMA foreign_keys = ON");
  // Temporary tables and sort spills in memory: SQLite would otherwise write
  // them to /var/tmp, outside the (private) data dir.
  db.exec("PRAGMA temp_store = MEMORY");
  sql::Transaction tx(db);
  migrate_schema(db, file.string());
  tx.commit();
}

JobStore::~JobStore() = default;

int JobStore::schema_version() const { return impl_->version(); }

int64_t JobStore::submit(const JobSpec& spec, double now) {
  if (spec.frames.empty()) throw StoreError("job '" + spec.name + "' has no frames");
  if (spec.spp <= 0) throw StoreError("job '" + spec.name + "': spp must be positive");
  if (spec.max_attempts <= 0)
    throw StoreError("job '" + spec.name + "': max_attempts must be positive");
  for (const Asset& a : spec.assets)
    if (const std::string why = asset_name_problem(a.name); !why.empty())
      throw StoreError("job '" + spec.name + "': asset name '" + a.name + "' " + why);
  if (spec.task_timeout && !(*spec.task_timeout > 0))
    throw StoreError("job '" + spec.name + "': task_timeout must be positive");
  if (const auto why = budget_problem(spec.budget, spec.spp))
    throw StoreError("job '" + spec.name + "': " + why->field + ": " + why->message);
  const RenderOverrides& o = spec.overrides;
  if (o.seed && *o.seed > uint64_t(INT64_MAX))
    throw StoreError("job '" + spec.name + "': seed above " + std::to_string(INT64_MAX));
  if (o.scale && !(*o.scale > 0 && *o.scale <= kMaxFilmScale))
    throw StoreError("job '" + spec.name + "': scale outside (0, " + exact_text(kMaxFilmScale) +
                     "]");
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const RenderBudget& b = spec.budget;
  sql::Stmt(db,
            "INSERT INTO jobs(id, name, scene, spp, priority, max_attempts, state, created, "
            "inputs_key, noise_target, min_spp, time_limit, aovs, layer_variance, seed, scale, "
            "task_timeout, half) "
            // Above every id ever used, deleted ones too (migration 0011).
            "VALUES((SELECT id + 1 FROM job_id_high_water), ?1, ?2, ?3, ?4, ?5, 'active', ?6, ?7, "
            "?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16)")
      .bind(1, spec.name)
      .bind(2, spec.scene)
      .bind(3, int64_t(spec.spp))
      .bind(4, int64_t(spec.priority))
      .bind(5, int64_t(spec.max_attempts))
      .bind(6, now)
      .bind(7, inputs_key(spec))
      .bind(8, b.noise_target)
      .bind(9, b.min_spp ? std::optional<int64_t>(*b.min_spp) : std::nullopt)
      .bind(10, b.time_limit)
      .bind(11, o.aovs.empty() ? std::nullopt : std::optional<std::string>(join_aovs(o.aovs)))
      .bind(12, int64_t(o.layer_variance))
      .bind(13, o.seed ? std::optional<int64_t>(int64_t(*o.seed)) : std::nullopt)
      .bind(14, o.scale)
      .bind(15, spec.task_timeout)
      .bind(16, int64_t(o.half))
      .run();
  const int64_t job = sqlite3_last_insert_rowid(db.get());
  for (size_t i = 0; i < spec.assets.size(); ++i)
    sql::Stmt(db, "INSERT INTO job_assets(job_id, ord, name, blob) VALUES(?1, ?2, ?3, ?4)")
        .bind(1, job)
        .bind(2, int64_t(i))
        .bind(3, spec.assets[i].name)
        .bind(4, spec.assets[i].blob)
        .run();
  const int split = spec.samples_per_task > 0 ? spec.samples_per_task : spec.spp;
  // Inserted in leasing order, so task ids follow (frame, sample range): a
  // page of the task list is a range of ids.
  std::vector<int> frames = spec.frames;
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  for (int frame : frames) {
    const auto state = spec.frame_states.find(frame);
    for (int b = 0; b < spec.spp; b += split) {
      sql::Stmt(db,
                "INSERT INTO tasks(job_id, frame, sample_begin, sample_end, state, frame_state) "
                "VALUES(?1, ?2, ?3, ?4, 'queued', ?5)")
          .bind(1, job)
          .bind(2, int64_t(frame))
          .bind(3, int64_t(b))
          .bind(4, int64_t(std::min(spec.spp, b + split)))
          .bind(5, state == spec.frame_states.end() ? std::string() : state->second)
          .run();
    }
  }
  tx.commit();
  return job;
}

std::optional<Lease> JobStore::lease(const std::string& worker, double now,
                                     const std::string& renderer, int* reused) {
  sql::Transaction tx(impl_->db);
  impl_->expire(now);
  if (reused) *reused = 0;
  std::optional<Lease> lease;
  while (const auto task = next_task(impl_->db, worker, impl_->options.blocklist_threshold)) {
    // An identical task is done already: take its result and look further.
    if (complete_from_identical_task(*impl_, *task, renderer, now)) {
      if (reused) ++*reused;
      continue;
    }
    lease = grant_lease(*impl_, *task, worker, renderer, now);
    break;
  }
  tx.commit();  // with no lease, still commits the requeued expired leases
  return lease;
}

std::optional<Lease> JobStore::current_lease(const std::string& lease_id) const {
  const auto task = impl_->leased_task(lease_id);
  if (!task) return std::nullopt;
  Lease lease;
  lease.lease_id = lease_id;
  lease.task = *task;
  describe_lease(*impl_, lease);
  return lease;
}

HeartbeatAnswer JobStore::heartbeat(const std::string& lease_id, double now) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const auto task = impl_->leased_task(lease_id);
  if (!task) {
    // Canceled tasks keep the lease id they had: tell that worker to stop (so
    // do tasks paused while leased by a vesper before schema 10).
    sql::Stmt s(db, "SELECT state FROM tasks WHERE lease_id = ?1");
    s.bind(1, lease_id);
    const bool stopped = s.step() && (s.text(0) == "canceled" || s.text(0) == "paused");
    return stopped ? HeartbeatAnswer::Stop : HeartbeatAnswer::StaleLease;
  }
  sql::Stmt(db, "UPDATE tasks SET lease_expiry = ?2 WHERE id = ?1")
      .bind(1, task->id)
      .bind(2, now + impl_->options.lease_seconds)
      .run();
  tx.commit();
  return HeartbeatAnswer::KeepRunning;
}

bool JobStore::complete(const std::string& lease_id, const std::string& result, double now,
                        const std::optional<FrameNoise>& result_noise,
                        const std::string& log_tail) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const auto task = impl_->leased_task(lease_id);
  if (!task) return false;
  sql::Stmt(db,
            "UPDATE tasks SET state = 'done', result = ?2, lease_id = NULL, lease_expiry = NULL, "
            "finished = ?3, log = ?4 WHERE id = ?1")
      .bind(1, task->id)
      .bind(2, result)
      .bind(3, now)
      .bind(4, log_tail)
      .run();
  // A frame of one task: its result is the frame's output, recorded with the completion.
  impl_->record_output_if_single_task_frame(*task, result, now, result_noise);
  impl_->settle_job(task->job_id, now);
  tx.commit();
  return true;
}

bool JobStore::fail(const std::string& lease_id, const std::string& log_tail, double now) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const auto task = impl_->leased_task(lease_id);
  if (!task) return false;
  impl_->record_failure(task->id, task->job_id, task->worker, log_tail, now);
  tx.commit();
  return true;
}

int JobStore::renew_leases(double now) {
  sql::Transaction tx(impl_->db);
  sql::Stmt(impl_->db,
            "UPDATE tasks SET lease_expiry = MAX(lease_expiry, ?1) WHERE state = 'leased'")
      .bind(1, now + impl_->options.lease_seconds)
      .run();
  const int n = sqlite3_changes(impl_->db.get());
  tx.commit();
  return n;
}

int JobStore::expire_leases(double now) {
  sql::Transaction tx(impl_->db);
  const int n = impl_->expire(now);
  tx.commit();
  return n;
}

std::vector<Task> JobStore::tasks(int64_t job, int64_t after, size_t limit) const {
  sql::Stmt s(impl_->db, (std::string("SELECT ") + kTaskColumns +
                          " FROM tasks WHERE job_id = ?1 AND id > ?2 ORDER BY id LIMIT ?3")
                             .c_str());
  s.bind(1, job).bind(2, after).bind(3, limit == 0 ? int64_t(-1) : int64_t(limit));
  std::vector<Task> out;
  while (s.step()) out.push_back(read_task(s));
  return out;
}

JobStore::ReadSnapshot::ReadSnapshot(JobStore& store) : store_(store) {
  store_.impl_->db.exec("BEGIN DEFERRED");
}
JobStore::ReadSnapshot::~ReadSnapshot() {
  try {
    store_.impl_->db.exec("COMMIT");
  } catch (const StoreError&) {
    // A read transaction has nothing to lose; the next BEGIN would fail loudly.
  }
}

std::vector<Asset> JobStore::assets(int64_t job) const { return impl_->assets(job); }

std::vector<FrameStatus> JobStore::frames(int64_t job) const {
  return impl_->frames(job, INT_MIN, INT_MAX);
}

std::vector<FrameStatus> JobStore::frames(int64_t job, int first, int last) const {
  return impl_->frames(job, first, last);
}

std::optional<FrameStatus> JobStore::frame(int64_t job, int frame) const {
  auto f = impl_->frames(job, frame, frame);
  if (f.empty()) return std::nullopt;
  return f[0];
}

std::string JobStore::record_frame_output(int64_t job, int frame, const std::string& blob,
                                          double now, const std::optional<FrameNoise>& noise) {
  sql::Transaction tx(impl_->db);
  const auto f = impl_->frames(job, frame, frame);
  if (f.empty() || !f[0].complete())
    throw StoreError("job " + std::to_string(job) + " frame " + std::to_string(frame) +
                     " is not finished; its output cannot be recorded");
  const std::string recorded = impl_->record_output(job, frame, blob, now);
  if (noise) impl_->record_noise(job, frame, *noise);  // changes nothing if recorded before
  tx.commit();
  return recorded;
}

std::vector<std::pair<int64_t, int>> JobStore::frames_awaiting_merge() const {
  // Frames of several tasks are those with a sample range beginning after 0
  // (an index of split tasks only): one-task frames, most of a big job, cost nothing.
  sql::Stmt s(impl_->db,
              "SELECT s.job_id, s.frame FROM (SELECT DISTINCT job_id, frame FROM tasks WHERE "
              "sample_begin > 0) s LEFT JOIN frame_outputs o ON o.job_id = s.job_id AND o.frame "
              "= s.frame WHERE o.blob IS NULL AND NOT EXISTS(SELECT 1 FROM tasks t WHERE "
              "t.job_id = s.job_id AND t.frame = s.frame AND t.state <> 'done') "
              "ORDER BY s.job_id, s.frame");
  std::vector<std::pair<int64_t, int>> out;
  while (s.step()) out.emplace_back(s.i64(0), int(s.i64(1)));
  return out;
}

std::vector<JobStore::UnreadOutput> JobStore::outputs_without_noise() const {
  sql::Stmt s(impl_->db,
              "SELECT job_id, frame, blob FROM frame_outputs WHERE noise_read = 0 "
              "ORDER BY job_id, frame");
  std::vector<UnreadOutput> out;
  while (s.step()) out.push_back({s.i64(0), int(s.i64(1)), s.text(2)});
  return out;
}

void JobStore::record_frame_noise(int64_t job, int frame, const FrameNoise& noise) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  impl_->record_noise(job, frame, noise);
  if (sqlite3_changes(db.get()) == 0) {
    sql::Stmt s(db, "SELECT 1 FROM frame_outputs WHERE job_id = ?1 AND frame = ?2");
    s.bind(1, job).bind(2, int64_t(frame));
    if (!s.step())
      throw StoreError("job " + std::to_string(job) + " frame " + std::to_string(frame) +
                       " has no output; its noise cannot be recorded");
  }
  tx.commit();
}

bool JobStore::blocked(int64_t job, const std::string& worker) const {
  sql::Stmt s(impl_->db,
              "SELECT COUNT(*) FROM worker_task_failures WHERE job_id = ?1 AND worker = ?2");
  s.bind(1, job).bind(2, worker);
  return s.step() && s.i64(0) >= impl_->options.blocklist_threshold;
}

std::vector<std::string> JobStore::blocked_workers(int64_t job) const {
  sql::Stmt s(impl_->db,
              "SELECT worker FROM worker_task_failures WHERE job_id = ?1 GROUP BY worker "
              "HAVING COUNT(*) >= ?2 ORDER BY worker");
  s.bind(1, job).bind(2, int64_t(impl_->options.blocklist_threshold));
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.text(0));
  return out;
}

}  // namespace vesper
