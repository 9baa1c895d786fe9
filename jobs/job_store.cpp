#include "jobs/job_store.h"

#include <algorithm>
#include <random>

#include "jobs/sqlite_db.h"

namespace vesper {

const char* to_string(TaskState s) {
  switch (s) {
    case TaskState::Queued:
      return "queued";
    case TaskState::Leased:
      return "leased";
    case TaskState::Done:
      return "done";
    case TaskState::Failed:
      return "failed";
    case TaskState::Canceled:
      return "canceled";
    case TaskState::Paused:
      return "paused";
  }
  return "?";
}
const char* to_string(JobState s) {
  switch (s) {
    case JobState::Active:
      return "active";
    case JobState::Paused:
      return "paused";
    case JobState::Canceled:
      return "canceled";
  }
  return "?";
}

namespace {

TaskState task_state(const std::string& s) {
  for (TaskState t : {TaskState::Queued, TaskState::Leased, TaskState::Done, TaskState::Failed,
                      TaskState::Canceled, TaskState::Paused})
    if (s == to_string(t)) return t;
  throw StoreError("unknown task state '" + s + "' in the store");
}
JobState job_state(const std::string& s) {
  for (JobState j : {JobState::Active, JobState::Paused, JobState::Canceled})
    if (s == to_string(j)) return j;
  throw StoreError("unknown job state '" + s + "' in the store");
}

// Schema migrations, applied in order; schema_version counts the applied ones.
const char* const kMigrations[] = {
    R"sql(
CREATE TABLE jobs(
  id INTEGER PRIMARY KEY, name TEXT NOT NULL, scene TEXT NOT NULL, spp INTEGER NOT NULL,
  priority INTEGER NOT NULL, max_attempts INTEGER NOT NULL, state TEXT NOT NULL, created REAL NOT NULL);
CREATE TABLE tasks(
  id INTEGER PRIMARY KEY, job_id INTEGER NOT NULL REFERENCES jobs(id), frame INTEGER NOT NULL,
  sample_begin INTEGER NOT NULL, sample_end INTEGER NOT NULL, state TEXT NOT NULL,
  attempts INTEGER NOT NULL DEFAULT 0, lease_id TEXT, worker TEXT NOT NULL DEFAULT '',
  lease_expiry REAL, result TEXT NOT NULL DEFAULT '', log TEXT NOT NULL DEFAULT '');
CREATE INDEX tasks_by_state ON tasks(state, job_id);
CREATE UNIQUE INDEX tasks_by_lease ON tasks(lease_id) WHERE lease_id IS NOT NULL;
CREATE TABLE worker_failures(
  job_id INTEGER NOT NULL, worker TEXT NOT NULL, failures INTEGER NOT NULL, PRIMARY KEY(job_id, worker));
)sql",
    // 2: assets (files the scene references) travel as blobs.
    R"sql(
CREATE TABLE job_assets(
  job_id INTEGER NOT NULL REFERENCES jobs(id), ord INTEGER NOT NULL, name TEXT NOT NULL,
  blob TEXT NOT NULL, PRIMARY KEY(job_id, ord), UNIQUE(job_id, name));
)sql",
    // 3: one output per finished frame, recorded once.
    R"sql(
CREATE TABLE frame_outputs(
  job_id INTEGER NOT NULL REFERENCES jobs(id), frame INTEGER NOT NULL, blob TEXT NOT NULL,
  created REAL NOT NULL, PRIMARY KEY(job_id, frame));
)sql",
    // 4: the blocklist counts the distinct tasks a worker failed in a job, so a
    // frame that crashes everywhere fails itself instead of blocking every
    // worker (the old per-worker counters are dropped: blocklists reset).
    R"sql(
DROP TABLE worker_failures;
CREATE TABLE worker_task_failures(
  job_id INTEGER NOT NULL, worker TEXT NOT NULL, task_id INTEGER NOT NULL,
  failures INTEGER NOT NULL, PRIMARY KEY(job_id, worker, task_id));
)sql",
    // 5: identical tasks are rendered once: a job's inputs key (scene, spp,
    // assets), the renderer (its executable's sha256) that produced each
    // result, and where a reused result came from.
    R"sql(
ALTER TABLE jobs ADD COLUMN inputs_key TEXT NOT NULL DEFAULT '';
ALTER TABLE tasks ADD COLUMN renderer TEXT NOT NULL DEFAULT '';
ALTER TABLE tasks ADD COLUMN reused_from INTEGER;
CREATE INDEX tasks_done_by_range ON tasks(frame, sample_begin, sample_end) WHERE state = 'done';
)sql",
};

// What makes two tasks identical besides their frame and sample range: the
// scene blob, the spp and the assets (name -> blob, in name order).
std::string inputs_key(const JobSpec& spec) {
  std::vector<std::string> assets;
  for (const Asset& a : spec.assets) assets.push_back(a.name + "=" + a.blob);
  std::sort(assets.begin(), assets.end());
  std::string key = spec.scene + ";spp=" + std::to_string(spec.spp);
  for (const auto& a : assets) key += ";" + a;
  return key;
}

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

constexpr const char* kTaskColumns =
    "id, job_id, frame, sample_begin, sample_end, state, attempts, worker, result, log, "
    "reused_from";

Task read_task(const sql::Stmt& s) {
  Task t;
  t.id = s.i64(0);
  t.job_id = s.i64(1);
  t.frame = int(s.i64(2));
  t.sample_begin = int(s.i64(3));
  t.sample_end = int(s.i64(4));
  t.state = task_state(s.text(5));
  t.attempts = int(s.i64(6));
  t.worker = s.text(7);
  t.result = s.text(8);
  t.log = s.text(9);
  t.reused_from = s.i64(10);  // NULL reads as 0
  return t;
}

}  // namespace

struct JobStore::Impl {
  sql::Db db;
  StoreOptions options;
  explicit Impl(const std::filesystem::path& file, StoreOptions o)
      : db(file.string()), options(o) {}

  int version() const {
    sql::Stmt s(db, "SELECT version FROM schema_version");
    return s.step() ? int(s.i64(0)) : 0;
  }

  // Failed attempt bookkeeping shared by fail() and lease expiry.
  void record_failure(int64_t task_id, int64_t job_id, const std::string& worker,
                      const std::string& log) {
    sql::Stmt(
        db,
        "UPDATE tasks SET attempts = attempts + 1, lease_id = NULL, lease_expiry = NULL, log = ?2, "
        "state = CASE WHEN attempts + 1 >= (SELECT max_attempts FROM jobs WHERE id = job_id) "
        "THEN 'failed' ELSE 'queued' END WHERE id = ?1")
        .bind(1, task_id)
        .bind(2, log)
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
  }

  int expire(double now) {
    std::vector<std::tuple<int64_t, int64_t, std::string>> expired;
    {
      sql::Stmt s(
          db, "SELECT id, job_id, worker FROM tasks WHERE state = 'leased' AND lease_expiry < ?1");
      s.bind(1, now);
      while (s.step()) expired.emplace_back(s.i64(0), s.i64(1), s.text(2));
    }
    for (const auto& [id, job, worker] : expired)
      record_failure(id, job, worker, "lease expired (worker lost)");
    return int(expired.size());
  }

  // The current task of a lease id, if the lease is still current.
  std::optional<Task> leased_task(const std::string& lease_id) const {
    sql::Stmt s(db, (std::string("SELECT ") + kTaskColumns +
                     " FROM tasks WHERE lease_id = ?1 AND state = 'leased'")
                        .c_str());
    s.bind(1, lease_id);
    if (!s.step()) return std::nullopt;
    return read_task(s);
  }

  std::optional<Task> task(int64_t id) const {
    sql::Stmt s(db, (std::string("SELECT ") + kTaskColumns + " FROM tasks WHERE id = ?1").c_str());
    s.bind(1, id);
    if (!s.step()) return std::nullopt;
    return read_task(s);
  }

  std::vector<Asset> assets(int64_t job) const {
    sql::Stmt s(db, "SELECT name, blob FROM job_assets WHERE job_id = ?1 ORDER BY ord");
    s.bind(1, job);
    std::vector<Asset> out;
    while (s.step()) out.push_back({s.text(0), s.text(1)});
    return out;
  }

  // Records a frame's output unless one is recorded already; returns the recorded blob.
  std::string record_output(int64_t job, int frame, const std::string& blob, double now) {
    sql::Stmt(db,
              "INSERT INTO frame_outputs(job_id, frame, blob, created) VALUES(?1, ?2, ?3, ?4) "
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

  std::vector<FrameStatus> frames(int64_t job, std::optional<int> only) const {
    sql::Stmt s(db,
                "SELECT t.frame, t.state, t.result, o.blob FROM tasks t LEFT JOIN frame_outputs o "
                "ON o.job_id = t.job_id AND o.frame = t.frame WHERE t.job_id = ?1 AND (?2 = 0 OR "
                "t.frame = ?3) ORDER BY t.frame, t.sample_begin");
    s.bind(1, job).bind(2, int64_t(only ? 1 : 0)).bind(3, int64_t(only.value_or(0)));
    std::vector<FrameStatus> out;
    while (s.step()) {
      const int frame = int(s.i64(0));
      if (out.empty() || out.back().frame != frame) {
        out.emplace_back();
        out.back().frame = frame;
        out.back().output = s.text(3);
      }
      FrameStatus& f = out.back();
      ++f.tasks;
      switch (task_state(s.text(1))) {
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
};

JobStore::JobStore(const std::filesystem::path& file, StoreOptions options)
    : impl_(std::make_unique<Impl>(file, options)) {
  auto& db = impl_->db;
  db.exec("PRAGMA journal_mode = WAL");
  db.exec("PRAGMA synchronous = FULL");  // a committed state change survives power loss
  db.exec("PRAGMA foreign_keys = ON");
  sql::Transaction tx(db);
  db.exec("CREATE TABLE IF NOT EXISTS schema_version(version INTEGER NOT NULL)");
  int v = impl_->version();
  if (v == 0 && !sql::Stmt(db, "SELECT 1 FROM schema_version").step())
    db.exec("INSERT INTO schema_version(version) VALUES(0)");
  const int latest = int(std::size(kMigrations));
  if (v > latest)
    throw StoreError("job store " + file.string() + " has schema version " + std::to_string(v) +
                     ", newer than this vesper understands (" + std::to_string(latest) + ")");
  for (; v < latest; ++v) db.exec(kMigrations[v]);
  sql::Stmt(db, "UPDATE schema_version SET version = ?1").bind(1, int64_t(latest)).run();
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
  auto& db = impl_->db;
  sql::Transaction tx(db);
  sql::Stmt(db,
            "INSERT INTO jobs(name, scene, spp, priority, max_attempts, state, created, "
            "inputs_key) VALUES(?1, ?2, ?3, ?4, ?5, 'active', ?6, ?7)")
      .bind(1, spec.name)
      .bind(2, spec.scene)
      .bind(3, int64_t(spec.spp))
      .bind(4, int64_t(spec.priority))
      .bind(5, int64_t(spec.max_attempts))
      .bind(6, now)
      .bind(7, inputs_key(spec))
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
  for (int frame : spec.frames)
    for (int b = 0; b < spec.spp; b += split) {
      sql::Stmt(db,
                "INSERT INTO tasks(job_id, frame, sample_begin, sample_end, state) VALUES(?1, ?2, "
                "?3, ?4, 'queued')")
          .bind(1, job)
          .bind(2, int64_t(frame))
          .bind(3, int64_t(b))
          .bind(4, int64_t(std::min(spec.spp, b + split)))
          .run();
    }
  tx.commit();
  return job;
}

std::optional<Lease> JobStore::lease(const std::string& worker, double now,
                                     const std::string& renderer, int* reused) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  impl_->expire(now);
  if (reused) *reused = 0;
  for (;;) {
    sql::Stmt pick(db,
                   "SELECT t.id, j.scene, j.spp FROM tasks t JOIN jobs j ON j.id = t.job_id "
                   "WHERE t.state = 'queued' AND j.state = 'active' AND ("
                   "  SELECT COUNT(*) FROM worker_task_failures f WHERE f.job_id = j.id AND "
                   "f.worker = ?1) < ?2 "
                   // A retry goes to a worker that has not failed this task, when there is one.
                   "ORDER BY j.priority DESC, j.id, EXISTS(SELECT 1 FROM worker_task_failures g "
                   "WHERE g.task_id = t.id AND g.worker = ?1), t.frame, t.sample_begin LIMIT 1");
    pick.bind(1, worker).bind(2, int64_t(impl_->options.blocklist_threshold));
    if (!pick.step()) {
      tx.commit();  // expired leases were requeued
      return std::nullopt;
    }
    const int64_t task_id = pick.i64(0);
    // The same task (inputs, frame, samples) already rendered by this renderer:
    // reuse its result instead of rendering it again, and look further.
    if (!renderer.empty()) {
      sql::Stmt same(db,
                     "SELECT d.id, d.result FROM tasks t JOIN jobs j ON j.id = t.job_id "
                     "JOIN tasks d ON d.state = 'done' AND d.frame = t.frame AND "
                     "d.sample_begin = t.sample_begin AND d.sample_end = t.sample_end AND "
                     "d.renderer = ?2 AND d.result <> '' AND d.id <> t.id "
                     "JOIN jobs dj ON dj.id = d.job_id AND dj.inputs_key = j.inputs_key "
                     "WHERE t.id = ?1 AND j.inputs_key <> '' ORDER BY d.id LIMIT 1");
      same.bind(1, task_id).bind(2, renderer);
      if (same.step()) {
        const int64_t source = same.i64(0);
        const std::string result = same.text(1);
        sql::Stmt(db,
                  "UPDATE tasks SET state = 'done', result = ?2, renderer = ?3, reused_from = ?4 "
                  "WHERE id = ?1")
            .bind(1, task_id)
            .bind(2, result)
            .bind(3, renderer)
            .bind(4, source)
            .run();
        const Task t = *impl_->task(task_id);
        const auto frame = impl_->frames(t.job_id, t.frame);
        if (frame.size() == 1 && frame[0].tasks == 1 && frame[0].complete())
          impl_->record_output(t.job_id, t.frame, result, now);
        if (reused) ++*reused;
        continue;
      }
    }
    Lease lease;
    lease.scene = pick.text(1);
    lease.spp = int(pick.i64(2));
    lease.lease_id = new_lease_id();
    lease.expiry = now + impl_->options.lease_seconds;
    sql::Stmt(db,
              "UPDATE tasks SET state = 'leased', lease_id = ?2, worker = ?3, lease_expiry = ?4, "
              "renderer = ?5 WHERE id = ?1")
        .bind(1, task_id)
        .bind(2, lease.lease_id)
        .bind(3, worker)
        .bind(4, lease.expiry)
        .bind(5, renderer)
        .run();
    lease.task = *impl_->leased_task(lease.lease_id);
    lease.assets = impl_->assets(lease.task.job_id);
    tx.commit();
    return lease;
  }
}

HeartbeatAnswer JobStore::heartbeat(const std::string& lease_id, double now) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const auto task = impl_->leased_task(lease_id);
  if (!task) {
    // Canceled and paused tasks keep the lease id they had: tell that worker to stop.
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

bool JobStore::complete(const std::string& lease_id, const std::string& result, double now) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const auto task = impl_->leased_task(lease_id);
  if (!task) return false;
  sql::Stmt(db,
            "UPDATE tasks SET state = 'done', result = ?2, lease_id = NULL, lease_expiry = NULL "
            "WHERE id = ?1")
      .bind(1, task->id)
      .bind(2, result)
      .run();
  // A frame of one task: its result is the frame's output, recorded with the completion.
  const auto frame = impl_->frames(task->job_id, task->frame);
  if (frame.size() == 1 && frame[0].tasks == 1 && frame[0].complete())
    impl_->record_output(task->job_id, task->frame, result, now);
  tx.commit();
  return true;
}

bool JobStore::fail(const std::string& lease_id, const std::string& log_tail, double) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  const auto task = impl_->leased_task(lease_id);
  if (!task) return false;
  impl_->record_failure(task->id, task->job_id, task->worker, log_tail);
  tx.commit();
  return true;
}

int JobStore::expire_leases(double now) {
  sql::Transaction tx(impl_->db);
  const int n = impl_->expire(now);
  tx.commit();
  return n;
}

namespace {
// Sets a job's state and moves its unfinished tasks; false for an unknown job.
bool set_job_state(sql::Db& db, int64_t job, const char* job_state, const char* task_sql) {
  sql::Transaction tx(db);
  sql::Stmt check(db, "SELECT 1 FROM jobs WHERE id = ?1");
  check.bind(1, job);
  if (!check.step()) return false;
  sql::Stmt(db, "UPDATE jobs SET state = ?2 WHERE id = ?1")
      .bind(1, job)
      .bind(2, std::string(job_state))
      .run();
  sql::Stmt(db, task_sql).bind(1, job).run();
  tx.commit();
  return true;
}
}  // namespace

// A canceled or paused job's leased tasks stop being leased at once: the
// worker's next heartbeat answers Stop, and its late upload is refused.
bool JobStore::cancel(int64_t job) {
  return set_job_state(impl_->db, job, "canceled",
                       "UPDATE tasks SET state = 'canceled', lease_expiry = NULL "
                       "WHERE job_id = ?1 AND state IN ('queued', 'leased', 'paused')");
}
bool JobStore::pause(int64_t job) {
  return set_job_state(impl_->db, job, "paused",
                       "UPDATE tasks SET state = 'paused', lease_expiry = NULL "
                       "WHERE job_id = ?1 AND state IN ('queued', 'leased')");
}
bool JobStore::resume(int64_t job) {
  return set_job_state(impl_->db, job, "active",
                       "UPDATE tasks SET state = 'queued' WHERE job_id = ?1 AND state = 'paused'");
}

int JobStore::retry_failed(int64_t job) {
  auto& db = impl_->db;
  sql::Transaction tx(db);
  sql::Stmt(
      db, "UPDATE tasks SET state = 'queued', attempts = 0 WHERE job_id = ?1 AND state = 'failed'")
      .bind(1, job)
      .run();
  const int n = sqlite3_changes(db.get());
  sql::Stmt(db, "DELETE FROM worker_task_failures WHERE job_id = ?1").bind(1, job).run();
  tx.commit();
  return n;
}

std::optional<JobSummary> JobStore::job(int64_t id) const {
  sql::Stmt s(impl_->db, "SELECT id, name, priority, state FROM jobs WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  JobSummary j;
  j.id = s.i64(0);
  j.name = s.text(1);
  j.priority = int(s.i64(2));
  j.state = job_state(s.text(3));
  sql::Stmt c(impl_->db, "SELECT state, COUNT(*) FROM tasks WHERE job_id = ?1 GROUP BY state");
  c.bind(1, id);
  while (c.step()) {
    const int n = int(c.i64(1));
    switch (task_state(c.text(0))) {
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

std::vector<Task> JobStore::tasks(int64_t job) const {
  sql::Stmt s(impl_->db, (std::string("SELECT ") + kTaskColumns +
                          " FROM tasks WHERE job_id = ?1 ORDER BY frame, sample_begin")
                             .c_str());
  s.bind(1, job);
  std::vector<Task> out;
  while (s.step()) out.push_back(read_task(s));
  return out;
}

std::vector<Asset> JobStore::assets(int64_t job) const { return impl_->assets(job); }

std::vector<FrameStatus> JobStore::frames(int64_t job) const {
  return impl_->frames(job, std::nullopt);
}

std::optional<FrameStatus> JobStore::frame(int64_t job, int frame) const {
  auto f = impl_->frames(job, frame);
  if (f.empty()) return std::nullopt;
  return f[0];
}

std::string JobStore::record_frame_output(int64_t job, int frame, const std::string& blob,
                                          double now) {
  sql::Transaction tx(impl_->db);
  const auto f = impl_->frames(job, frame);
  if (f.empty() || !f[0].complete())
    throw StoreError("job " + std::to_string(job) + " frame " + std::to_string(frame) +
                     " is not finished; its output cannot be recorded");
  const std::string recorded = impl_->record_output(job, frame, blob, now);
  tx.commit();
  return recorded;
}

std::vector<std::pair<int64_t, int>> JobStore::frames_awaiting_merge() const {
  sql::Stmt s(impl_->db,
              "SELECT t.job_id, t.frame FROM tasks t LEFT JOIN frame_outputs o ON o.job_id = "
              "t.job_id AND o.frame = t.frame WHERE o.blob IS NULL GROUP BY t.job_id, t.frame "
              "HAVING COUNT(*) > 1 AND SUM(t.state <> 'done') = 0 ORDER BY t.job_id, t.frame");
  std::vector<std::pair<int64_t, int>> out;
  while (s.step()) out.emplace_back(s.i64(0), int(s.i64(1)));
  return out;
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
