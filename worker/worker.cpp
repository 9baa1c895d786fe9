#include "worker/worker.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "common/json_parse.h"
#include "common/sha256.h"
#include "common/utf8.h"
#include "jobs/frame_states.h"
#include "protocol/worker_messages.h"
#include "worker/backoff.h"
#include "worker/blob_cache.h"
#include "worker/cache_eviction.h"
#include "worker/lease_retry.h"
#include "worker/render_command.h"
#include "worker/server_api.h"
#include "worker/task_dir.h"
#include "worker/task_runner.h"
#include "worker/uploader.h"
#include "worker/worker_identity.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {

using namespace worker_detail;

namespace {

constexpr size_t kLogTail = 64 * 1024;      // what the server keeps of a failure log
constexpr size_t kDoneLogTail = 16 * 1024;  // and of a done task's log

std::string hostname() {
  char buf[256] = {0};
  if (::gethostname(buf, sizeof buf - 1) != 0 || !buf[0]) return "worker";
  return buf;
}

// Unique per Worker (pid + random), so that several workers (threads or
// processes) sharing one cache dir never collide on a temp name.
std::string instance_name() {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx",
                static_cast<unsigned long long>(std::mt19937_64{std::random_device{}()}()));
  return std::to_string(::getpid()) + "-" + buf;
}

}  // namespace

// The worker's states, as in Flamenco's worker (awake → fetch task → run
// task): register → lease → [fetch → run → upload → complete] → lease …
enum class WorkerState { Register, Lease, Stopped, Fatal };

struct Worker::Impl {
  Worker& self;
  WorkerConfig cfg;
  std::unique_ptr<ServerApi> api;
  std::unique_ptr<BlobCache> cache;
  std::unique_ptr<WorkerIdentity> identity;  // the id kept across restarts
  Backoff backoff;
  mutable std::mutex id_mutex;
  std::string worker_id;
  std::string instance = instance_name();
  int temp_counter = 0;
  int leased = 0;
  // Seconds a task with this (scene, sample count) took last time, for the
  // heartbeat's progress estimate.
  std::map<std::string, double> durations;
  // sha256 of the renderer executable: the server reuses results of identical
  // tasks only between workers with the very same renderer build.
  std::string renderer_id;

  Impl(Worker& w, WorkerConfig c)
      : self(w), cfg(std::move(c)), backoff(cfg.idle_backoff_min, cfg.idle_backoff_max) {}

  bool stopping() const { return self.stop_.load(); }
  std::string unique_name() { return instance + "-" + std::to_string(++temp_counter); }

  bool start();
  WorkerState register_worker();
  WorkerState lease();
  void say_goodbye();
  void work_on(const protocol::LeaseResponse& l);
  std::optional<fs::path> fetch(const protocol::LeaseResponse& l, LeaseRetry& retry);
  void keep_cache_under_cap(const protocol::LeaseResponse& l, const std::vector<Asset>& assets);
  std::optional<fs::path> run(const protocol::LeaseResponse& l, const fs::path& task_dir,
                              double& seconds, std::string& log, LeaseRetry& retry);
  bool heartbeat(const protocol::LeaseResponse& l, double progress, LeaseRetry& retry);
  void upload_and_complete(const protocol::LeaseResponse& l, const fs::path& out, double seconds,
                           const std::string& log, LeaseRetry& retry);
  void fail(const protocol::LeaseResponse& l, const std::string& log);
  void drop(const protocol::LeaseResponse& l, const std::string& why);
};

Worker::Worker(WorkerConfig config) : impl_(std::make_unique<Impl>(*this, std::move(config))) {}
Worker::~Worker() = default;

void Worker::request_stop() noexcept { stop_.store(true); }

std::string Worker::worker_id() const {
  std::lock_guard<std::mutex> lock(impl_->id_mutex);
  return impl_->worker_id;
}

int Worker::run() {
  if (!impl_->start()) return 1;
  WorkerState state = WorkerState::Register;
  for (;;) {
    switch (state) {
      case WorkerState::Register:
        state = impl_->register_worker();
        break;
      case WorkerState::Lease:
        state = impl_->lease();
        break;
      case WorkerState::Stopped:
        impl_->say_goodbye();
        return 0;
      case WorkerState::Fatal:
        return 1;
    }
  }
}

// Checks the configuration and fills in its defaults; false if the worker cannot run.
bool Worker::Impl::start() {
  if (cfg.server_url.empty()) {
    spdlog::error("worker: no server URL");
    return false;
  }
  if (cfg.vesper_binary.empty() || ::access(cfg.vesper_binary.c_str(), X_OK) != 0) {
    spdlog::error("worker: renderer '{}' is not an executable file", cfg.vesper_binary.string());
    return false;
  }
  if (cfg.name.empty()) cfg.name = hostname();
  if (cfg.reuse_results) renderer_id = sha256_file(cfg.vesper_binary).value_or("");
  if (cfg.cache_dir.empty()) cfg.cache_dir = fs::temp_directory_path() / "vesper-worker-cache";
  std::error_code ec;
  fs::create_directories(cfg.cache_dir / "tmp", ec);
  if (ec) {
    spdlog::error("worker: cannot create cache dir {}: {}", cfg.cache_dir.string(), ec.message());
    return false;
  }
  api = std::make_unique<ServerApi>(cfg.server_url, cfg.token);
  cache = std::make_unique<BlobCache>(*api, cfg.cache_dir);
  identity = std::make_unique<WorkerIdentity>(cfg.cache_dir);
  return true;
}

// Register (again, if the server forgot us), with the id this worker had
// (before a restart: kept in the cache dir), so the server keeps it: a
// transport error or 5xx is retried with back-off (the server may be
// restarting); 400/401 is fatal.
WorkerState Worker::Impl::register_worker() {
  for (;;) {
    if (stopping()) return WorkerState::Stopped;
    const std::string previous = self.worker_id().empty() ? identity->saved_id() : self.worker_id();
    const HttpResponse r = api->register_worker({cfg.name, previous});
    if (r.status == 200 || r.status == 201) {
      try {
        std::lock_guard<std::mutex> lock(id_mutex);
        worker_id = json::parse(r.body).get<protocol::RegisterResponse>().worker_id;
      } catch (const std::exception& e) {
        spdlog::error("worker: bad register answer: {}", e.what());
        return WorkerState::Fatal;
      }
      identity->save(self.worker_id());
      spdlog::info("worker '{}' registered as {} with {}", cfg.name, self.worker_id(),
                   cfg.server_url);
      backoff.reset();
      return WorkerState::Lease;
    }
    if (r.status == 401 || r.status == 400) {
      spdlog::error("worker: register refused: {}", describe(r));
      return WorkerState::Fatal;
    }
    spdlog::warn("worker: register failed ({}); retrying", describe(r));
    if (!backoff.sleep(self.stop_)) return WorkerState::Stopped;
  }
}

// A clean stop tells the server, which lists this worker "offline" rather
// than "lost" (docs/farm.md, "Worker states"). Best effort: one try.
void Worker::Impl::say_goodbye() {
  const std::string id = self.worker_id();
  if (id.empty()) return;
  const HttpResponse r = api->goodbye({id});
  if (r.status != 200) spdlog::warn("worker: goodbye not delivered ({})", describe(r));
}

// Asks for one task and works on it. 204 = no work (back off, or stop when
// exit_when_idle), 404 = the server forgot us (register again), 401 = fatal.
WorkerState Worker::Impl::lease() {
  if (stopping()) return WorkerState::Stopped;
  if (cfg.max_tasks >= 0 && leased >= cfg.max_tasks) return WorkerState::Stopped;
  const auto back_off = [&] {
    return backoff.sleep(self.stop_) ? WorkerState::Lease : WorkerState::Stopped;
  };
  const HttpResponse r = api->lease({self.worker_id(), renderer_id});
  if (r.status == 204) return cfg.exit_when_idle ? WorkerState::Stopped : back_off();
  if (r.status == 404) {
    spdlog::warn("worker: the server does not know worker {}; registering again", self.worker_id());
    return WorkerState::Register;
  }
  if (r.status == 401) {
    spdlog::error("worker: lease refused: {}", describe(r));
    return WorkerState::Fatal;
  }
  if (r.status != 200) {
    spdlog::warn("worker: lease failed ({}); backing off", describe(r));
    return back_off();
  }
  backoff.reset();
  protocol::LeaseResponse lease;
  try {
    lease = json::parse(r.body).get<protocol::LeaseResponse>();
  } catch (const std::exception& e) {
    spdlog::error("worker: bad lease answer ({}): {}", e.what(), r.body);
    return back_off();
  }
  ++leased;
  work_on(lease);
  return WorkerState::Lease;
}

// fetch → run → upload → complete; a problem of the task at any step fails
// it, a server away for longer than the lease could live drops it (the
// worker carries on either way).
void Worker::Impl::work_on(const protocol::LeaseResponse& l) {
  spdlog::info("task {} (job {}, frame {}, samples [{}, {}) of {}{}, attempt {}): leased",
               l.task.id, l.task.job_id, l.task.frame, l.task.sample_begin, l.task.sample_end,
               l.spp, describe_budget(l), l.task.attempt);
  LeaseRetry retry(l.lease_seconds, Backoff(cfg.idle_backoff_min, cfg.idle_backoff_max),
                   self.stop_);
  const std::optional<fs::path> task_dir = fetch(l, retry);
  if (!task_dir) return;
  double seconds = 0;
  std::string log;  // the render's log tail, kept by the server as the task's log
  const std::optional<fs::path> out = run(l, *task_dir, seconds, log, retry);
  if (!out) return;
  upload_and_complete(l, *out, seconds, log, retry);
}

// Marks the task's blobs used now, then evicts the least recently used
// others while the cache is over its cap.
void Worker::Impl::keep_cache_under_cap(const protocol::LeaseResponse& l,
                                        const std::vector<Asset>& assets) {
  std::set<std::string> in_use{l.scene};
  mark_used(cfg.cache_dir / (l.scene + ".json"));
  for (const Asset& a : assets) {
    in_use.insert(a.blob);
    mark_used(asset_cache_file(cfg.cache_dir, a.blob));
  }
  const Evicted e = evict_lru(cfg.cache_dir, std::uintmax_t(cfg.cache_max_bytes), in_use);
  if (e.blobs)
    spdlog::info("worker: cache over its cap: evicted {} blobs ({} bytes)", e.blobs, e.bytes);
}

namespace {
// The assets the lease's frame reads (jobs/frame_states.h, frame_assets):
// of a `####` sequence, its own frame's file, not every frame of the job.
// All of them when the scene cannot be read as JSON (the render says why).
std::vector<Asset> task_assets(const protocol::LeaseResponse& l, const fs::path& scene_file) {
  std::vector<Asset> assets;  // the job store's spelling of the lease's assets
  for (const protocol::AssetRef& a : l.assets) assets.push_back({a.name, a.blob});
  try {
    return frame_assets(read_json_file(scene_file, "the scene"), l.task.frame, assets);
  } catch (const std::exception&) {
    return assets;
  }
}
}  // namespace

// The scene and its assets, from the verified cache, in a task directory.
std::optional<fs::path> Worker::Impl::fetch(const protocol::LeaseResponse& l, LeaseRetry& retry) {
  const fs::path scene_file = cfg.cache_dir / (l.scene + ".json");
  BlobCache::Fetched got =
      cache->fetch(l.scene, scene_file, "scene", unique_name(), retry, l.task.id);
  const std::vector<Asset> assets =
      got.problem.empty() ? task_assets(l, scene_file) : std::vector<Asset>{};
  for (size_t i = 0; got.problem.empty() && i < assets.size(); ++i)
    got = cache->fetch(assets[i].blob, asset_cache_file(cfg.cache_dir, assets[i].blob),
                       "asset '" + assets[i].name + "'", unique_name(), retry, l.task.id);
  if (got.gave_up) {
    drop(l, got.problem);
    return std::nullopt;
  }
  std::string problem = got.problem;
  if (problem.empty()) {
    keep_cache_under_cap(l, assets);
    try {
      return materialise_task_dir(cfg.cache_dir, l.scene, assets, unique_name());
    } catch (const std::exception& e) {
      problem = std::string("cannot prepare the task directory: ") + e.what();
    }
  }
  spdlog::error("task {}: {}", l.task.id, problem);
  fail(l, "worker: " + problem);
  return std::nullopt;
}

// Renders in a child process, heartbeating; returns the output file, or
// nullopt when the task was dropped or failed (then reported and cleaned up).
std::optional<fs::path> Worker::Impl::run(const protocol::LeaseResponse& l,
                                          const fs::path& task_dir, double& seconds,
                                          std::string& log, LeaseRetry& retry) {
  const fs::path out =
      cfg.cache_dir / "tmp" / ("render-" + unique_name() + render_output_extension(l));
  const std::vector<std::string> argv = render_command(l, cfg, task_dir / "scene.json", out);
  const std::string duration_key =
      l.scene + ":" + std::to_string(l.task.sample_end - l.task.sample_begin);
  RenderWatch watch;
  watch.heartbeat_seconds = std::max(0.05, std::min(cfg.heartbeat_seconds, l.lease_seconds / 3));
  watch.kill_grace_seconds = cfg.kill_grace_seconds;
  watch.log_tail_bytes = kLogTail;
  watch.timeout_seconds = l.task_timeout;
  if (auto it = durations.find(duration_key); it != durations.end())
    watch.expected_seconds = it->second;
  const RenderRun r = run_render(argv, watch, [&](double p) { return heartbeat(l, p, retry); });
  seconds = r.seconds;
  std::error_code ec;
  if (r.end == RenderRun::End::NotStarted) {
    spdlog::error("task {}: {}", l.task.id, r.status);
    fail(l, "worker: " + r.status + "\n" + command_line(argv));
    return std::nullopt;
  }
  if (r.end == RenderRun::End::Dropped) {
    fs::remove(out, ec);
    ++self.dropped_;
    return std::nullopt;
  }
  if (r.end == RenderRun::End::TimedOut) {
    const std::string why = fmt::format(
        "the render ran longer than the task timeout of {} s and was killed (pid {}, {})",
        *l.task_timeout, r.pid, r.status);
    spdlog::warn("task {}: {}", l.task.id, why);
    fail(l, "worker: " + why + "\ncommand: " + command_line(argv) + "\n--- stderr (tail) ---\n" +
                r.stderr_tail);
    fs::remove(out, ec);
    return std::nullopt;
  }
  if (!r.succeeded || !fs::exists(out)) {
    const std::string status = r.succeeded ? "exit code 0 but no output file" : r.status;
    spdlog::warn("task {}: render failed ({}) after {:.2f} s", l.task.id, status, seconds);
    fail(l, "vesper render failed: " + status + "\ncommand: " + command_line(argv) +
                "\n--- stderr (tail) ---\n" + r.stderr_tail);
    fs::remove(out, ec);
    return std::nullopt;
  }
  durations[duration_key] = seconds;
  log = utf8_tail(r.stderr_tail, kDoneLogTail);
  return out;
}

// One heartbeat; false when the render must stop ("stop": job canceled;
// 409: the lease is stale). A transport failure waits for the next
// beat; an accepted beat renews the lease (`retry`'s deadline).
bool Worker::Impl::heartbeat(const protocol::LeaseResponse& l, double progress, LeaseRetry& retry) {
  const HttpResponse hb = api->heartbeat({l.lease_id, progress});
  bool stop = false;
  if (hb.status == 200) {
    try {
      stop = json::parse(hb.body).get<protocol::HeartbeatResponse>().answer ==
             protocol::HeartbeatAnswer::Stop;
    } catch (const json::exception&) {
      // An answer this worker does not understand is not an order to stop.
    }
    if (!stop) retry.confirmed();
  }
  if (hb.status == 409 || stop) {
    spdlog::info("task {}: {}; killing the render", l.task.id,
                 hb.status == 409 ? "lease is stale" : "the server says stop");
    return false;
  }
  if (hb.status != 200) spdlog::warn("task {}: heartbeat failed ({})", l.task.id, describe(hb));
  return true;
}

// Upload the result (content addressed), then complete; the temp file always goes.
void Worker::Impl::upload_and_complete(const protocol::LeaseResponse& l, const fs::path& out,
                                       double seconds, const std::string& log, LeaseRetry& retry) {
  const Upload up = upload_result(*api, out, l.task.id, retry);
  std::error_code ec;
  fs::remove(out, ec);
  if (!up.blob) {
    if (up.gave_up)
      drop(l, "the upload of the result: " + up.problem);
    else
      fail(l, "worker: upload of the result failed: " + up.problem);
    return;
  }
  switch (complete_task(*api, l.lease_id, *up.blob, log, l.task.id, retry)) {
    case Completion::Completed:
      spdlog::info("task {}: done in {:.2f} s, result {}", l.task.id, seconds, *up.blob);
      ++self.completed_;
      break;
    case Completion::Stale:
      ++self.dropped_;
      break;
    case Completion::GaveUp:
      drop(l, "the completion was not taken");
      break;
    case Completion::Failed:
      break;
  }
}

// The server stayed away or in trouble for as long as the lease could live:
// not the task's fault, so no POST /fail (no attempt charged, no blocklist);
// the lease expires on the server and the task is rendered again.
void Worker::Impl::drop(const protocol::LeaseResponse& l, const std::string& why) {
  spdlog::warn(
      "task {}: dropped, the server could not be reached in time ({}); it will be "
      "rendered again",
      l.task.id, why);
  ++self.dropped_;
}

void Worker::Impl::fail(const protocol::LeaseResponse& l, const std::string& log) {
  const HttpResponse f = api->fail({l.lease_id, utf8_tail(log, kLogTail)});
  if (f.status == 409)
    spdlog::info("task {}: fail refused, lease is stale", l.task.id);
  else if (!f.ok())
    spdlog::warn("task {}: could not report the failure ({})", l.task.id, describe(f));
  ++self.failed_;
}

}  // namespace vesper
