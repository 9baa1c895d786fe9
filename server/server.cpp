// The HTTP layer: routes, auth, size limits, JSON errors. This is the only
// file that includes cpp-httplib.
#include "server/server.h"

#include <httplib.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <sys/socket.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "common/secret_token.h"
#include "common/sha256.h"
#include "jobs/job_store.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/json_body.h"
#include "server/merge.h"
#include "server/metrics.h"
#include "server/tokens.h"
#include "server/worker_registry.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

constexpr const char* kApi = "/api/v1";
constexpr size_t kMaxLogTail = 64 * 1024;

enum class Role { None, Submitter, Worker, Either };

json summary_json(const JobSummary& j) {
  return {{"id", j.id},
          {"name", j.name},
          {"priority", j.priority},
          {"state", to_string(j.state)},
          {"counts",
           {{"queued", j.queued},
            {"leased", j.leased},
            {"done", j.done},
            {"failed", j.failed},
            {"canceled", j.canceled},
            {"paused", j.paused}}},
          {"total", j.total()},
          {"finished", j.finished()}};
}

json task_json(const Task& t) {
  json j{{"id", t.id},
         {"job_id", t.job_id},
         {"frame", t.frame},
         {"sample_begin", t.sample_begin},
         {"sample_end", t.sample_end},
         {"state", to_string(t.state)},
         {"attempts", t.attempts},
         {"worker", t.worker},
         {"result", t.result},
         {"has_log", !t.log.empty()}};
  if (t.reused_from) j["reused_from"] = t.reused_from;
  return j;
}

void send_json(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump() + "\n", "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message,
                const std::string& path = {}) {
  json body{{"error", message}};
  if (!path.empty()) body["path"] = path;
  send_json(res, status, body);
}

int64_t parse_id(const std::string& s) {
  try {
    size_t used = 0;
    const long long v = std::stoll(s, &used);
    if (used == s.size() && v > 0) return v;
  } catch (const std::exception&) {
  }
  throw ApiError(404, "no such id '" + s + "'");
}

int parse_frame(const std::string& s) {
  try {
    size_t used = 0;
    const long long v = std::stoll(s, &used);
    if (used == s.size() && v >= INT32_MIN && v <= INT32_MAX) return int(v);
  } catch (const std::exception&) {
  }
  throw ApiError(404, "no such frame '" + s.substr(0, 80) + "'");
}

// Streams a file as the response body.
void send_file(httplib::Response& res, const fs::path& path, uintmax_t size,
               const char* content_type) {
  res.status = 200;
  res.set_content_provider(size_t(size), content_type,
                           [path, in = std::shared_ptr<std::ifstream>()](
                               size_t offset, size_t length, httplib::DataSink& sink) mutable {
                             if (!in) {
                               in = std::make_shared<std::ifstream>(path, std::ios::binary);
                               if (!*in) return false;
                             }
                             std::string buf(std::min<size_t>(length, 1 << 20), '\0');
                             in->seekg(std::streamoff(offset));
                             in->read(buf.data(), std::streamsize(buf.size()));
                             const auto n = size_t(in->gcount());
                             if (n == 0) return false;
                             return sink.write(buf.data(), n);
                           });
}

std::string bearer(const httplib::Request& req) {
  const std::string h = req.get_header_value("Authorization");
  constexpr std::string_view prefix = "Bearer ";
  if (h.size() <= prefix.size() || h.compare(0, prefix.size(), prefix) != 0) return {};
  return h.substr(prefix.size());
}

}  // namespace

struct Server::Impl {
  ServerConfig config;
  Tokens tokens;
  BlobStore blobs;
  WorkerRegistry workers;
  std::mutex store_mutex;  // JobStore holds one SQLite connection: one caller at a time
  std::unique_ptr<JobStore> store;
  httplib::Server http;
  std::thread http_thread, reaper_thread;
  int bound_port = 0;
  int listen_socket = -1;  // set by the socket options callback, before bind
  bool started = false, stopped = false;
  std::mutex stop_mutex;
  std::condition_variable stop_cv;

  // Clock
  std::mutex clock_mutex;
  double last_now = 0;

  // Metrics since start
  std::atomic<uint64_t> leases_granted{0};
  std::atomic<uint64_t> reused_tasks{0};
  std::mutex metrics_mutex;
  std::map<int, uint64_t> http_codes;

  // Live leases seen by this process: progress for task listings, the worker
  // for last-seen updates. In memory only (lost on restart, refilled by the
  // next lease).
  struct LiveLease {
    int64_t task_id = 0;
    std::string worker_id;
    double expiry = 0;
    double progress = 0;
  };
  std::mutex live_mutex;
  std::map<std::string, LiveLease> live;  // by lease id

  // Merged frame outputs. A frame is merged by one thread at a time
  // (`merging`); the store records the output once. A failed merge is kept
  // here (in memory) and retried on request after merge_retry_seconds.
  fs::path merger;  // the vesper binary; empty: merging unavailable
  std::string merger_problem;
  std::atomic<bool> stopping{false};
  std::mutex merge_mutex;
  std::condition_variable merge_cv;
  bool merge_scan = true;  // the background merger should look for frames to merge
  std::set<std::pair<int64_t, int>> merging;
  struct MergeFailure {
    std::string error;
    std::chrono::steady_clock::time_point when;
  };
  std::map<std::pair<int64_t, int>, MergeFailure> merge_failures;
  std::thread merge_thread;
  std::atomic<uint64_t> merge_counter{0};

  explicit Impl(ServerConfig c)
      : config(prepare(std::move(c))),
        tokens(load_or_create_tokens(config.data_dir / "tokens.json")),
        blobs(config.data_dir / "blobs"),
        workers(config.data_dir / "workers.json"),
        store(std::make_unique<JobStore>(
            config.data_dir / "jobs.sqlite",
            StoreOptions{config.lease_seconds, config.blocklist_threshold})) {
    merger = find_vesper_binary(config.vesper_binary, merger_problem);
    if (merger.empty())
      spdlog::warn("merged frames of several tasks unavailable: {}", merger_problem);
    // Merges killed with a previous server left only temp files: nothing was recorded.
    std::error_code ec;
    fs::remove_all(config.data_dir / "merge-tmp", ec);
    fs::create_directories(config.data_dir / "merge-tmp", ec);
  }

  static ServerConfig prepare(ServerConfig c) {
    if (c.data_dir.empty()) throw std::invalid_argument("server: data_dir is empty");
    if (!fs::exists(c.data_dir)) {
      fs::create_directories(c.data_dir);
      fs::permissions(c.data_dir, fs::perms::owner_all, fs::perm_options::replace);
    }
    if (c.lease_seconds <= 0) throw std::invalid_argument("server: lease_seconds must be positive");
    if (c.threads < 1) c.threads = 1;
    return c;
  }

  double now() {
    const double t =
        config.clock
            ? config.clock()
            : std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                  .count();
    std::lock_guard lock(clock_mutex);
    last_now = std::max(last_now, t);
    return last_now;
  }

  // ---- routing helpers ----

  bool authorized(const httplib::Request& req, Role role) const {
    if (role == Role::None) return true;
    const std::string token = bearer(req);
    if (token.empty()) return false;
    // Evaluate both comparisons regardless, in constant time.
    const bool sub = constant_time_equal(token, tokens.submitter);
    const bool wrk = constant_time_equal(token, tokens.worker);
    switch (role) {
      case Role::Submitter:
        return sub;
      case Role::Worker:
        return wrk;
      case Role::Either:
        return sub || wrk;
      case Role::None:
        break;
    }
    return true;
  }

  using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

  Handler wrap(Role role, bool json_body, Handler h) {
    return [this, role, json_body, h = std::move(h)](const httplib::Request& req,
                                                     httplib::Response& res) {
      if (!authorized(req, role)) {
        res.set_header("WWW-Authenticate", "Bearer");
        send_error(res, 401,
                   std::string("missing or wrong bearer token (this endpoint needs the ") +
                       (role == Role::Submitter ? "submitter"
                        : role == Role::Worker  ? "worker"
                                                : "submitter or worker") +
                       " token from the server's tokens.json)");
        return;
      }
      if (json_body && req.body.size() > config.max_json_bytes) {
        send_error(res, 413,
                   "JSON body of " + std::to_string(req.body.size()) +
                       " bytes exceeds the limit of " + std::to_string(config.max_json_bytes));
        return;
      }
      try {
        h(req, res);
      } catch (const ApiError& e) {
        send_error(res, e.status(), e.what(), e.path());
      } catch (const std::exception& e) {
        spdlog::error("{} {}: {}", req.method, req.path, e.what());
        send_error(res, 500, std::string("internal error: ") + e.what());
      }
    };
  }

  void get(const std::string& pattern, Role role, Handler h) {
    http.Get(pattern, wrap(role, false, std::move(h)));
  }
  void post(const std::string& pattern, Role role, Handler h) {
    http.Post(pattern, wrap(role, true, std::move(h)));
  }

  // ---- handlers ----

  json body_of(const httplib::Request& req) { return parse_json_body(req.body); }

  JobSummary job_or_404(int64_t id) {
    auto j = store->job(id);
    if (!j) throw ApiError(404, "no job " + std::to_string(id));
    return *j;
  }

  void submit_job(const httplib::Request& req, httplib::Response& res) {
    const json body = body_of(req);
    const JobSpec spec = parse_job_request(body);
    if (!blobs.exists(spec.scene))
      throw ApiError(
          400,
          "no blob " + spec.scene + ": upload the scene first (PUT " + kApi + "/blobs/{sha256})",
          "/scene");
    for (size_t i = 0; i < spec.assets.size(); ++i)
      if (!blobs.exists(spec.assets[i].blob))
        throw ApiError(400,
                       "no blob " + spec.assets[i].blob + " for asset '" + spec.assets[i].name +
                           "': upload it first (PUT " + kApi + "/blobs/{sha256})",
                       "/assets/" + std::to_string(i) + "/blob");
    const int64_t n = task_count(spec);
    const std::string dry = req.get_param_value("dry_run");
    if (dry == "1" || dry == "true") {
      send_json(res, 200,
                {{"dry_run", true},
                 {"name", spec.name},
                 {"frame_count", spec.frames.size()},
                 {"task_count", n}});
      return;
    }
    int64_t id = 0;
    {
      std::lock_guard lock(store_mutex);
      id = store->submit(spec, now());
    }
    spdlog::info("job {} '{}' submitted: {} frames, {} tasks", id, spec.name, spec.frames.size(),
                 n);
    res.set_header("Location", std::string(kApi) + "/jobs/" + std::to_string(id));
    send_json(res, 201, {{"id", id}, {"task_count", n}});
  }

  void list_jobs(const httplib::Request&, httplib::Response& res) {
    json arr = json::array();
    {
      std::lock_guard lock(store_mutex);
      for (const auto& j : store->jobs()) arr.push_back(summary_json(j));
    }
    send_json(res, 200, {{"jobs", arr}});
  }

  void get_job(const httplib::Request& req, httplib::Response& res) {
    const int64_t id = parse_id(req.matches[1]);
    json out;
    std::vector<Task> tasks;
    {
      std::lock_guard lock(store_mutex);
      out = summary_json(job_or_404(id));
      tasks = store->tasks(id);
      out["blocked_workers"] = store->blocked_workers(id);
    }
    std::map<int64_t, double> progress;
    {
      std::lock_guard lock(live_mutex);
      for (const auto& [lease_id, l] : live) progress[l.task_id] = l.progress;
    }
    json arr = json::array();
    for (const Task& t : tasks) {
      json tj = task_json(t);
      if (t.state == TaskState::Leased && progress.count(t.id)) tj["progress"] = progress[t.id];
      arr.push_back(std::move(tj));
    }
    out["tasks"] = std::move(arr);
    send_json(res, 200, out);
  }

  void job_action(const httplib::Request& req, httplib::Response& res) {
    const int64_t id = parse_id(req.matches[1]);
    const std::string action = req.matches[2];
    json out;
    {
      std::lock_guard lock(store_mutex);
      job_or_404(id);
      if (action == "cancel") {
        store->cancel(id);
      } else if (action == "pause") {
        store->pause(id);
      } else if (action == "resume") {
        store->resume(id);
      } else {
        out["requeued"] = store->retry_failed(id);
      }
      out["job"] = summary_json(job_or_404(id));
    }
    spdlog::info("job {}: {}", id, action);
    send_json(res, 200, out);
  }

  void task_log(const httplib::Request& req, httplib::Response& res) {
    const int64_t job = parse_id(req.matches[1]);
    const int64_t task = parse_id(req.matches[2]);
    std::vector<Task> tasks;
    {
      std::lock_guard lock(store_mutex);
      job_or_404(job);
      tasks = store->tasks(job);
    }
    for (const Task& t : tasks)
      if (t.id == task) {
        res.status = 200;
        res.set_content(t.log, "text/plain; charset=utf-8");
        return;
      }
    throw ApiError(404, "job " + std::to_string(job) + " has no task " + std::to_string(task));
  }

  void register_worker(const httplib::Request& req, httplib::Response& res) {
    const json body = body_of(req);
    const JsonObject o(body, "", {"name"});
    const std::string name = o.string("name");
    if (name.size() > 128) throw ApiError(400, "name longer than 128 characters", "/name");
    const std::string id = workers.add(name, now());
    spdlog::info("worker '{}' registered as {}", name, id);
    send_json(res, 200, {{"worker_id", id}});
  }

  void list_workers(const httplib::Request&, httplib::Response& res) {
    std::map<std::string, int> leases;
    {
      std::lock_guard lock(live_mutex);
      for (const auto& [id, l] : live) ++leases[l.worker_id];
    }
    json arr = json::array();
    for (const WorkerInfo& w : workers.list())
      arr.push_back({{"worker_id", w.id},
                     {"name", w.name},
                     {"registered", w.registered},
                     {"last_seen", w.last_seen},
                     {"leases", leases[w.id]}});
    send_json(res, 200, {{"workers", arr}, {"now", now()}});
  }

  void lease(const httplib::Request& req, httplib::Response& res) {
    const json body = body_of(req);
    const JsonObject o(body, "", {"worker_id", "renderer"});
    const std::string worker = o.string("worker_id");
    // The worker's renderer identity (sha256 of its executable): identical
    // tasks done by the same renderer are not rendered again.
    const std::string renderer = o.opt_string("renderer").value_or("");
    if (!renderer.empty() && !is_sha256_hex(renderer))
      throw ApiError(400, "expected the renderer's sha256 (64 lower-case hex digits)", "/renderer");
    const double t = now();
    if (!workers.touch(worker, t))
      throw ApiError(404,
                     "unknown worker '" + worker.substr(0, 80) + "': register first (POST " + kApi +
                         "/workers/register)",
                     "/worker_id");
    std::optional<Lease> l;
    int reused = 0;
    {
      std::lock_guard lock(store_mutex);
      l = store->lease(worker, t, renderer, &reused);
    }
    if (reused > 0) {
      reused_tasks += reused;
      wake_merger();  // reused tasks may have finished frames of several tasks
    }
    if (!l) {
      res.status = 204;
      return;
    }
    ++leases_granted;
    json assets = json::array();
    for (const Asset& a : l->assets) assets.push_back({{"name", a.name}, {"blob", a.blob}});
    {
      std::lock_guard lock(live_mutex);
      live[l->lease_id] = LiveLease{l->task.id, worker, l->expiry, 0};
    }
    send_json(res, 200,
              {{"lease_id", l->lease_id},
               {"expiry", l->expiry},
               {"lease_seconds", config.lease_seconds},
               {"scene", l->scene},
               {"spp", l->spp},
               {"assets", std::move(assets)},
               {"task",
                {{"id", l->task.id},
                 {"job_id", l->task.job_id},
                 {"frame", l->task.frame},
                 {"sample_begin", l->task.sample_begin},
                 {"sample_end", l->task.sample_end},
                 {"attempt", l->task.attempts + 1}}}});
  }

  // Notes a call on a live lease (last-seen of its worker); forgets a lease
  // that ended.
  void note_lease(const std::string& lease_id, double t, bool ended,
                  std::optional<double> progress = std::nullopt) {
    std::string worker;
    {
      std::lock_guard lock(live_mutex);
      auto it = live.find(lease_id);
      if (it == live.end()) return;
      worker = it->second.worker_id;
      if (progress) it->second.progress = *progress;
      it->second.expiry = t + config.lease_seconds;
      if (ended) live.erase(it);
    }
    workers.touch(worker, t);
  }

  [[noreturn]] static void stale(const std::string& lease_id) {
    throw ApiError(409,
                   "stale lease '" + lease_id.substr(0, 80) +
                       "': it expired, was re-leased, or its task was canceled; drop the task",
                   "/lease_id");
  }

  void heartbeat(const httplib::Request& req, httplib::Response& res) {
    const json body = body_of(req);
    const JsonObject o(body, "", {"lease_id", "progress"});
    const std::string lease_id = o.string("lease_id");
    const double progress = o.number("progress", 0, 0, 1);
    const double t = now();
    HeartbeatAnswer a;
    {
      std::lock_guard lock(store_mutex);
      a = store->heartbeat(lease_id, t);
    }
    note_lease(lease_id, t, a != HeartbeatAnswer::KeepRunning, progress);
    if (a == HeartbeatAnswer::StaleLease) stale(lease_id);
    send_json(res, 200, {{"answer", a == HeartbeatAnswer::KeepRunning ? "keep_running" : "stop"}});
  }

  void complete(const httplib::Request& req, httplib::Response& res) {
    const json body = body_of(req);
    const JsonObject o(body, "", {"lease_id", "result"});
    const std::string lease_id = o.string("lease_id");
    const std::string result = o.string("result");
    if (!is_sha256_hex(result))
      throw ApiError(400,
                     "expected the SHA-256 of the uploaded result blob (64 lower-case hex digits)",
                     "/result");
    if (!blobs.exists(result))
      throw ApiError(
          400, "no blob " + result + ": upload the result first (PUT " + kApi + "/blobs/{sha256})",
          "/result");
    const double t = now();
    bool ok;
    {
      std::lock_guard lock(store_mutex);
      ok = store->complete(lease_id, result, t);
    }
    note_lease(lease_id, t, true);
    if (!ok) stale(lease_id);
    wake_merger();  // the task may have finished a frame of several tasks
    send_json(res, 200, {{"ok", true}});
  }

  void fail(const httplib::Request& req, httplib::Response& res) {
    const json body = body_of(req);
    const JsonObject o(body, "", {"lease_id", "log"});
    const std::string lease_id = o.string("lease_id");
    std::string log = o.opt_string("log").value_or("");
    if (log.size() > kMaxLogTail) log = log.substr(log.size() - kMaxLogTail);
    const double t = now();
    bool ok;
    {
      std::lock_guard lock(store_mutex);
      ok = store->fail(lease_id, log, t);
    }
    note_lease(lease_id, t, true);
    if (!ok) stale(lease_id);
    send_json(res, 200, {{"ok", true}});
  }

  void put_blob(const httplib::Request& req, httplib::Response& res) {
    const std::string hash = req.matches[1];
    const bool created = blobs.put(hash, req.body);
    send_json(res, created ? 201 : 200, {{"sha256", hash}, {"size", req.body.size()}});
  }

  void get_blob(const httplib::Request& req, httplib::Response& res) {
    const std::string hash = req.matches[1];
    const auto file = blobs.file(hash);
    const auto size = blobs.size(hash);
    if (!file || !size) throw ApiError(404, "no blob " + hash);
    send_file(res, *file, *size, "application/octet-stream");
  }

  // ---- merged frames ----

  void wake_merger() {
    {
      std::lock_guard lock(merge_mutex);
      merge_scan = true;
    }
    merge_cv.notify_all();
  }

  enum class Output { Ready, Pending, TasksFailed, Unavailable, MergeFailed, Stopping };
  struct FrameOutput {
    Output state = Output::Pending;
    std::string blob;     // Ready
    std::string message;  // otherwise
  };

  static std::string frame_name(int64_t job, int frame) {
    return "frame " + std::to_string(frame) + " of job " + std::to_string(job);
  }

  // The output of a frame, merging it first if it needs a merge and none
  // ran yet (or, with `retry`, the last one failed more than
  // merge_retry_seconds ago). Waits for a merge of the same frame that is
  // in flight. nullopt: the job has no such frame.
  std::optional<FrameOutput> frame_output(int64_t job, int frame, bool retry) {
    const auto key = std::make_pair(job, frame);
    for (;;) {
      std::optional<FrameStatus> f;
      {
        std::lock_guard lock(store_mutex);
        f = store->frame(job, frame);
      }
      if (!f) return std::nullopt;
      if (!f->output.empty()) return FrameOutput{Output::Ready, f->output, {}};
      if (f->failed + f->canceled > 0)
        return FrameOutput{Output::TasksFailed,
                           {},
                           frame_name(job, frame) +
                               " will not finish: " + std::to_string(f->failed) +
                               " task(s) failed and " + std::to_string(f->canceled) +
                               " canceled (POST .../retry-failed requeues failed tasks)"};
      if (!f->complete())
        return FrameOutput{Output::Pending,
                           {},
                           frame_name(job, frame) +
                               " is not finished yet: " + std::to_string(f->done) + " of " +
                               std::to_string(f->tasks) + " tasks done"};
      if (f->tasks == 1) {  // completed before outputs were recorded (an older store)
        std::lock_guard lock(store_mutex);
        return FrameOutput{
            Output::Ready, store->record_frame_output(job, frame, f->results[0], now()), {}};
      }
      if (merger.empty())
        return FrameOutput{Output::Unavailable, {}, "merging is unavailable: " + merger_problem};
      {
        std::unique_lock lock(merge_mutex);
        if (merging.count(key)) {  // another thread merges it: wait, then look again
          merge_cv.wait(lock, [&] { return !merging.count(key) || stopping.load(); });
          if (stopping.load()) return FrameOutput{Output::Stopping, {}, "the server is stopping"};
          if (auto it = merge_failures.find(key); it != merge_failures.end())
            return FrameOutput{Output::MergeFailed, {}, it->second.error};
          continue;
        }
        if (auto it = merge_failures.find(key); it != merge_failures.end()) {
          const double age =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second.when)
                  .count();
          if (!retry || age < config.merge_retry_seconds)
            return FrameOutput{Output::MergeFailed, {}, it->second.error};
        }
        merging.insert(key);
      }
      FrameOutput out;
      try {
        out = merge(job, frame, f->results);
      } catch (const std::exception& e) {
        out = FrameOutput{Output::MergeFailed, {}, std::string("merge failed: ") + e.what()};
      }
      {
        std::lock_guard lock(merge_mutex);
        merging.erase(key);
        if (out.state == Output::MergeFailed)
          merge_failures[key] = MergeFailure{out.message, std::chrono::steady_clock::now()};
        else
          merge_failures.erase(key);
      }
      merge_cv.notify_all();
      return out;
    }
  }

  // Runs `vesper merge` over the frame's results, stores the EXR as a blob
  // and records it. Killed at any point before the record, it leaves nothing
  // recorded (a stray temp file in merge-tmp/ is removed at the next start).
  FrameOutput merge(int64_t job, int frame, const std::vector<std::string>& results) {
    std::vector<fs::path> inputs;
    for (const std::string& r : results) {
      auto file = blobs.file(r);
      if (!file) return {Output::MergeFailed, {}, "the result blob " + r + " of a task is missing"};
      inputs.push_back(*file);
    }
    const fs::path out = config.data_dir / "merge-tmp" /
                         (std::to_string(job) + "-" + std::to_string(frame) + "-" +
                          std::to_string(++merge_counter) + "-" + random_hex(8) + ".exr");
    spdlog::info("{}: merging {} sample ranges", frame_name(job, frame), inputs.size());
    const auto started = std::chrono::steady_clock::now();
    const MergeRun run = run_vesper_merge(merger, inputs, out, stopping);
    if (run.aborted) return {Output::Stopping, {}, run.error};
    if (!run.ok) {
      spdlog::error("{}: {}", frame_name(job, frame), run.error);
      return {Output::MergeFailed, {}, run.error};
    }
    std::string bytes;
    {
      std::ifstream in(out, std::ios::binary);
      std::ostringstream ss;
      ss << in.rdbuf();
      bytes = ss.str();
    }
    std::error_code ec;
    fs::remove(out, ec);
    const std::string hash = sha256_hex(bytes);
    blobs.put(hash, bytes);
    std::string recorded;
    {
      std::lock_guard lock(store_mutex);
      recorded = store->record_frame_output(job, frame, hash, now());
    }
    spdlog::info("{}: merged into {} in {:.2f} s", frame_name(job, frame), recorded,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    return {Output::Ready, recorded, {}};
  }

  // Background: merges every finished frame that waits for a merge, after
  // each completion (and once at start, for merges a restart interrupted).
  // Failed merges are not retried here; a request retries them later.
  void merger_loop() {
    for (;;) {
      {
        std::unique_lock lock(merge_mutex);
        merge_cv.wait(lock, [&] { return merge_scan || stopping.load(); });
        if (stopping.load()) return;
        merge_scan = false;
      }
      if (merger.empty()) continue;
      std::vector<std::pair<int64_t, int>> todo;
      try {
        std::lock_guard lock(store_mutex);
        todo = store->frames_awaiting_merge();
      } catch (const std::exception& e) {
        spdlog::error("merger: {}", e.what());
      }
      for (const auto& [job, frame] : todo) {
        if (stopping.load()) return;
        try {
          frame_output(job, frame, /*retry=*/false);
        } catch (const std::exception& e) {
          spdlog::error("merger: {}: {}", frame_name(job, frame), e.what());
        }
      }
    }
  }

  void list_frames(const httplib::Request& req, httplib::Response& res) {
    const int64_t id = parse_id(req.matches[1]);
    std::vector<FrameStatus> frames;
    {
      std::lock_guard lock(store_mutex);
      job_or_404(id);
      frames = store->frames(id);
    }
    std::map<std::pair<int64_t, int>, std::string> failures;
    {
      std::lock_guard lock(merge_mutex);
      for (const auto& [key, f] : merge_failures)
        if (key.first == id) failures[key] = f.error;
    }
    json arr = json::array();
    for (const FrameStatus& f : frames) {
      json fj{{"frame", f.frame}, {"tasks", f.tasks}, {"done", f.done}};
      if (!f.output.empty() || (f.complete() && f.tasks == 1)) {
        fj["state"] = "ready";
        fj["blob"] = f.output.empty() ? f.results[0] : f.output;
      } else if (f.failed + f.canceled > 0) {
        fj["state"] = "failed";
        fj["error"] = std::to_string(f.failed) + " task(s) failed, " + std::to_string(f.canceled) +
                      " canceled";
      } else if (auto it = failures.find({id, f.frame}); f.complete() && it != failures.end()) {
        fj["state"] = "failed";
        fj["error"] = it->second;
      } else {
        fj["state"] = "pending";
      }
      arr.push_back(std::move(fj));
    }
    send_json(res, 200, {{"frames", arr}});
  }

  void get_frame(const httplib::Request& req, httplib::Response& res) {
    const int64_t id = parse_id(req.matches[1]);
    const int frame = parse_frame(req.matches[2]);
    {
      std::lock_guard lock(store_mutex);
      job_or_404(id);
    }
    const auto out = frame_output(id, frame, /*retry=*/true);
    if (!out)
      throw ApiError(404, "job " + std::to_string(id) + " has no frame " + req.matches[2].str());
    switch (out->state) {
      case Output::Ready:
        break;
      case Output::Pending:
      case Output::TasksFailed:
        throw ApiError(409, out->message);
      case Output::Unavailable:
      case Output::Stopping:
        throw ApiError(503, out->message);
      case Output::MergeFailed:
        throw ApiError(500, out->message);
    }
    const auto file = blobs.file(out->blob);
    const auto size = blobs.size(out->blob);
    if (!file || !size)
      throw ApiError(500, "the output blob " + out->blob + " of " + frame_name(id, frame) +
                              " is missing from the blob store");
    res.set_header("X-Vesper-Blob", out->blob);
    send_file(res, *file, *size, "image/x-exr");
  }

  void metrics(const httplib::Request&, httplib::Response& res) {
    MetricsSnapshot m;
    for (TaskState s : {TaskState::Queued, TaskState::Leased, TaskState::Done, TaskState::Failed,
                        TaskState::Canceled, TaskState::Paused})
      m.tasks_by_state[to_string(s)] = 0;
    {
      std::lock_guard lock(store_mutex);
      const auto jobs = store->jobs();
      m.jobs = int64_t(jobs.size());
      for (const auto& j : jobs) {
        m.tasks_by_state["queued"] += j.queued;
        m.tasks_by_state["leased"] += j.leased;
        m.tasks_by_state["done"] += j.done;
        m.tasks_by_state["failed"] += j.failed;
        m.tasks_by_state["canceled"] += j.canceled;
        m.tasks_by_state["paused"] += j.paused;
      }
    }
    m.workers = int64_t(workers.list().size());
    m.leases_granted = leases_granted.load();
    m.tasks_reused = reused_tasks.load();
    {
      std::lock_guard lock(metrics_mutex);
      m.http_requests_by_code = http_codes;
    }
    res.status = 200;
    res.set_content(prometheus_text(m), "text/plain; version=0.0.4; charset=utf-8");
  }

  void install_routes() {
    const std::string api = kApi;
    auto bind = [this](void (Impl::*fn)(const httplib::Request&, httplib::Response&)) {
      return [this, fn](const httplib::Request& req, httplib::Response& res) {
        (this->*fn)(req, res);
      };
    };
    auto healthz = [](const httplib::Request&, httplib::Response& res) {
      res.status = 200;
      res.set_content("ok\n", "text/plain");
    };
    get("/healthz", Role::None, healthz);
    get(api + "/healthz", Role::None, healthz);
    get("/metrics", Role::Either, bind(&Impl::metrics));
    get(api + "/metrics", Role::Either, bind(&Impl::metrics));

    post(api + "/jobs", Role::Submitter, bind(&Impl::submit_job));
    get(api + "/jobs", Role::Submitter, bind(&Impl::list_jobs));
    get(api + R"(/jobs/([^/]+))", Role::Submitter, bind(&Impl::get_job));
    post(api + R"(/jobs/([^/]+)/(cancel|pause|resume|retry-failed))", Role::Submitter,
         bind(&Impl::job_action));
    get(api + R"(/jobs/([^/]+)/tasks/([^/]+)/log)", Role::Submitter, bind(&Impl::task_log));
    get(api + R"(/jobs/([^/]+)/frames)", Role::Submitter, bind(&Impl::list_frames));
    get(api + R"(/jobs/([^/]+)/frames/([^/]+))", Role::Submitter, bind(&Impl::get_frame));

    post(api + "/workers/register", Role::Worker, bind(&Impl::register_worker));
    get(api + "/workers", Role::Either, bind(&Impl::list_workers));
    post(api + "/lease", Role::Worker, bind(&Impl::lease));
    post(api + "/heartbeat", Role::Worker, bind(&Impl::heartbeat));
    post(api + "/complete", Role::Worker, bind(&Impl::complete));
    post(api + "/fail", Role::Worker, bind(&Impl::fail));

    // Blob names are validated by BlobStore (400 for anything but 64 hex
    // digits), so the route takes any rest of the path.
    http.Put(api + "/blobs/(.*)", wrap(Role::Either, false, bind(&Impl::put_blob)));
    get(api + "/blobs/(.*)", Role::Either, bind(&Impl::get_blob));  // also HEAD

    // JSON bodies for errors produced by httplib itself (404 no route, 413
    // over the payload limit, 400 unparsable request).
    http.set_error_handler(httplib::Server::HandlerWithResponse([this](const httplib::Request& req,
                                                                       httplib::Response& res) {
      if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
      std::string msg = res.status == 404   ? "no such endpoint: " + req.method + " " + req.path
                        : res.status == 413 ? "request body exceeds the limit of " +
                                                  std::to_string(config.max_blob_bytes) + " bytes"
                                            : "HTTP " + std::to_string(res.status);
      send_error(res, res.status, msg);
      return httplib::Server::HandlerResponse::Handled;
    }));
    // Counted before the response is written (the logger runs after it), so
    // a client that got an answer sees it in the next /metrics.
    http.set_post_routing_handler([this](const httplib::Request&, httplib::Response& res) {
      std::lock_guard lock(metrics_mutex);
      ++http_codes[res.status];
    });
    http.set_logger([](const httplib::Request& req, const httplib::Response& res) {
      spdlog::debug("{} {} -> {}", req.method, req.path, res.status);
    });
  }

  void reaper() {
    double interval = config.reaper_interval > 0 ? config.reaper_interval
                                                 : std::min(5.0, config.lease_seconds / 4);
    std::unique_lock lk(stop_mutex);
    while (
        !stop_cv.wait_for(lk, std::chrono::duration<double>(interval), [&] { return stopped; })) {
      lk.unlock();
      try {
        const double t = now();
        int n;
        {
          std::lock_guard lock(store_mutex);
          n = store->expire_leases(t);
        }
        if (n) spdlog::warn("{} expired lease(s) requeued", n);
        std::lock_guard lock(live_mutex);
        for (auto it = live.begin(); it != live.end();)
          it = it->second.expiry < t ? live.erase(it) : std::next(it);
      } catch (const std::exception& e) {
        spdlog::error("lease reaper: {}", e.what());
      }
      lk.lock();
    }
  }
};

Server::Server(ServerConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}

Server::~Server() { stop(); }

int Server::start() {
  Impl& s = *impl_;
  if (s.started) throw std::logic_error("Server::start called twice");
  s.started = true;
  const int threads = s.config.threads;
  s.http.new_task_queue = [threads] { return new httplib::ThreadPool(size_t(threads)); };
  s.http.set_payload_max_length(s.config.max_blob_bytes);
  s.http.set_keep_alive_timeout(5);
  // Responses go out as headers + body; without TCP_NODELAY the body waits for
  // the client's delayed ACK (~40 ms per keep-alive request, vesper_farm_bench).
  s.http.set_tcp_nodelay(true);
  s.http.set_read_timeout(30);
  s.http.set_write_timeout(30);
  // Not cpp-httplib's default options: those set SO_REUSEPORT, which lets a
  // second server bind the same port and silently take half the requests.
  // SO_REUSEADDR alone still allows a restart over TIME_WAIT connections.
  s.http.set_socket_options([&s](int sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    s.listen_socket = sock;
  });
  s.install_routes();
  if (s.config.port == 0) {
    s.bound_port = s.http.bind_to_any_port(s.config.host);
    if (s.bound_port < 0) s.bound_port = 0;
  } else {
    s.bound_port = s.http.bind_to_port(s.config.host, s.config.port) ? s.config.port : 0;
  }
  if (s.bound_port <= 0)
    throw std::runtime_error("server: cannot bind " + s.config.host + ":" +
                             std::to_string(s.config.port));
  // Debian's cpp-httplib is compiled with a listen backlog of 5: 50 workers
  // connecting at once overflow it and wait 1 s for a SYN retry
  // (vesper_farm_bench). listen() again on the bound socket raises it.
  if (s.listen_socket >= 0 && ::listen(s.listen_socket, SOMAXCONN) != 0)
    spdlog::warn("server: cannot raise the listen backlog: {}", std::strerror(errno));
  s.http_thread = std::thread([&s] { s.http.listen_after_bind(); });
  // stop() is a no-op until the accept loop runs: wait for it.
  for (int i = 0; i < 5000 && !s.http.is_running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  s.reaper_thread = std::thread([&s] { s.reaper(); });
  s.merge_thread = std::thread([&s] { s.merger_loop(); });
  spdlog::info("vesper server on http://{}:{} (data {})", s.config.host, s.bound_port,
               s.config.data_dir.string());
  return s.bound_port;
}

void Server::stop() {
  Impl& s = *impl_;
  {
    std::lock_guard lock(s.stop_mutex);
    if (s.stopped || !s.started) {
      s.stopped = true;
      return;
    }
    s.stopped = true;
  }
  s.stop_cv.notify_all();
  {
    std::lock_guard lock(s.merge_mutex);
    s.stopping = true;
  }
  s.merge_cv.notify_all();
  s.http.stop();
  if (s.http_thread.joinable()) s.http_thread.join();
  if (s.reaper_thread.joinable()) s.reaper_thread.join();
  if (s.merge_thread.joinable()) s.merge_thread.join();
  try {
    s.workers.save();
  } catch (const std::exception& e) {
    spdlog::error("saving workers: {}", e.what());
  }
}

int Server::port() const { return impl_->bound_port; }
std::string Server::url() const {
  return "http://" + impl_->config.host + ":" + std::to_string(impl_->bound_port);
}
std::string Server::submitter_token() const { return impl_->tokens.submitter; }
std::string Server::worker_token() const { return impl_->tokens.worker; }

}  // namespace vesper
