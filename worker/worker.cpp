#include "worker/worker.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "common/sha256.h"
#include "process/child_process.h"
#include "worker/http_client.h"
#include "worker/render_progress.h"
#include "worker/task_dir.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

using Clock = std::chrono::steady_clock;
using vesper::ChildProcess;
using worker_detail::HttpClient;
using worker_detail::HttpResponse;

constexpr const char* kApi = "/api/v1";
constexpr size_t kLogTail = 64 * 1024;  // what the server keeps of a failure log

std::string describe(const HttpResponse& r) {
  if (r.status == 0) return "transport error: " + r.error;
  std::string msg = "HTTP " + std::to_string(r.status);
  try {
    const json j = json::parse(r.body);
    if (j.contains("error")) msg += ": " + j.at("error").get<std::string>();
  } catch (...) {
  }
  return msg;
}

std::string hostname() {
  char buf[256] = {0};
  if (::gethostname(buf, sizeof buf - 1) != 0 || !buf[0]) return "worker";
  return buf;
}

std::string tail_of(std::string s, size_t n) {
  if (s.size() > n) s.erase(0, s.size() - n);
  return s;
}

}  // namespace

struct Worker::Impl {
  WorkerConfig cfg;
  std::unique_ptr<HttpClient> http;
  mutable std::mutex id_mutex;
  std::string worker_id;
  std::mt19937_64 rng{std::random_device{}()};
  double backoff = 0;
  int render_counter = 0;
  // Seconds a task with this (scene, sample count) took last time, for the
  // heartbeat's progress estimate.
  std::map<std::string, double> durations;
  // Unique per Worker, so that several workers (threads or processes) can
  // share one cache dir without their temp files colliding.
  std::string instance;
  // sha256 of the renderer executable: the server reuses results of identical
  // tasks only between workers with the very same renderer build.
  std::string renderer_id;

  explicit Impl(WorkerConfig c) : cfg(std::move(c)) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(rng()));
    instance = std::to_string(::getpid()) + "-" + buf;
  }
};

Worker::Worker(WorkerConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}
Worker::~Worker() = default;

void Worker::request_stop() noexcept { stop_.store(true); }

std::string Worker::worker_id() const {
  std::lock_guard<std::mutex> lock(impl_->id_mutex);
  return impl_->worker_id;
}

namespace {

// Sleeps for `seconds` in 50 ms slices; returns false early if stop was requested.
bool sleep_unless_stopped(const std::atomic<bool>& stop, double seconds) {
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(seconds));
  while (Clock::now() < deadline) {
    if (stop.load()) return false;
    const Clock::duration left = deadline - Clock::now();
    std::this_thread::sleep_for(std::min<Clock::duration>(std::chrono::milliseconds(50), left));
  }
  return !stop.load();
}

}  // namespace

// ---- the task, split into small steps ------------------------------------------------------

namespace {

struct LeasedTask {
  std::string lease_id, scene;
  int spp = 0, sample_begin = 0, sample_end = 0, frame = 0, attempt = 0;
  std::string id, job_id;  // as the server spells them (numbers or strings)
  double lease_seconds = 60;
  std::vector<Asset> assets;
  // A sample range that is not the whole frame renders a partial (exact
  // sample sums) for the server's `vesper merge`.
  bool partial() const { return sample_begin != 0 || sample_end != spp; }
};

std::string id_string(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

LeasedTask parse_lease(const json& j) {
  LeasedTask t;
  t.lease_id = j.at("lease_id").get<std::string>();
  t.scene = j.at("scene").get<std::string>();
  t.spp = j.at("spp").get<int>();
  t.lease_seconds = j.value("lease_seconds", 60.0);
  const json& task = j.at("task");
  t.id = id_string(task.at("id"));
  t.job_id = id_string(task.at("job_id"));
  t.frame = task.value("frame", 0);
  t.attempt = task.value("attempt", 0);
  t.sample_begin = task.value("sample_begin", 0);
  t.sample_end = task.value("sample_end", t.spp);
  if (j.contains("assets"))
    for (const json& a : j.at("assets"))
      t.assets.push_back({a.at("name").get<std::string>(), a.at("blob").get<std::string>()});
  return t;
}

}  // namespace

int Worker::run() {
  Impl& w = *impl_;
  WorkerConfig& cfg = w.cfg;
  if (cfg.server_url.empty()) {
    spdlog::error("worker: no server URL");
    return 1;
  }
  if (cfg.vesper_binary.empty() || ::access(cfg.vesper_binary.c_str(), X_OK) != 0) {
    spdlog::error("worker: renderer '{}' is not an executable file", cfg.vesper_binary.string());
    return 1;
  }
  if (cfg.name.empty()) cfg.name = hostname();
  if (cfg.reuse_results) w.renderer_id = sha256_file(cfg.vesper_binary).value_or("");
  if (cfg.cache_dir.empty()) cfg.cache_dir = fs::temp_directory_path() / "vesper-worker-cache";
  std::error_code ec;
  fs::create_directories(cfg.cache_dir / "tmp", ec);
  if (ec) {
    spdlog::error("worker: cannot create cache dir {}: {}", cfg.cache_dir.string(), ec.message());
    return 1;
  }
  cfg.idle_backoff_min = std::max(cfg.idle_backoff_min, 0.001);
  cfg.idle_backoff_max = std::max(cfg.idle_backoff_max, cfg.idle_backoff_min);
  w.http = std::make_unique<HttpClient>(cfg.server_url, cfg.token);

  // Jittered exponential back-off: sleep uniform in [b/2, b], b doubling up to the max.
  auto backoff_sleep = [&]() -> bool {
    w.backoff =
        w.backoff <= 0 ? cfg.idle_backoff_min : std::min(w.backoff * 2, cfg.idle_backoff_max);
    std::uniform_real_distribution<double> jitter(0.5, 1.0);
    return sleep_unless_stopped(stop_, w.backoff * jitter(w.rng));
  };

  // Register (again, if the server forgot us). Returns 0 ok, 1 fatal, 2 stopped.
  auto register_worker = [&]() -> int {
    for (;;) {
      if (stop_.load()) return 2;
      const HttpResponse r = w.http->post_json(std::string(kApi) + "/workers/register",
                                               json{{"name", cfg.name}}.dump());
      if (r.status == 200 || r.status == 201) {
        try {
          std::lock_guard<std::mutex> lock(w.id_mutex);
          w.worker_id = json::parse(r.body).at("worker_id").get<std::string>();
        } catch (const std::exception& e) {
          spdlog::error("worker: bad register answer: {}", e.what());
          return 1;
        }
        spdlog::info("worker '{}' registered as {} with {}", cfg.name, worker_id(), cfg.server_url);
        w.backoff = 0;
        return 0;
      }
      if (r.status == 401 || r.status == 400) {
        spdlog::error("worker: register refused: {}", describe(r));
        return 1;
      }
      spdlog::warn("worker: register failed ({}); retrying", describe(r));
      if (!backoff_sleep()) return 2;
    }
  };

  if (const int rc = register_worker(); rc != 0) return rc == 2 ? 0 : 1;

  int processed = 0;
  for (;;) {
    if (stop_.load()) return 0;
    if (cfg.max_tasks >= 0 && processed >= cfg.max_tasks) return 0;
    const HttpResponse r = w.http->post_json(
        std::string(kApi) + "/lease",
        (w.renderer_id.empty() ? json{{"worker_id", worker_id()}}
                               : json{{"worker_id", worker_id()}, {"renderer", w.renderer_id}})
            .dump());
    if (r.status == 204) {
      if (cfg.exit_when_idle) return 0;
      if (!backoff_sleep()) return 0;
      continue;
    }
    if (r.status == 404) {
      spdlog::warn("worker: the server does not know worker {}; registering again", worker_id());
      if (const int rc = register_worker(); rc != 0) return rc == 2 ? 0 : 1;
      continue;
    }
    if (r.status == 401) {
      spdlog::error("worker: lease refused: {}", describe(r));
      return 1;
    }
    if (r.status != 200) {
      spdlog::warn("worker: lease failed ({}); backing off", describe(r));
      if (!backoff_sleep()) return 0;
      continue;
    }
    w.backoff = 0;
    LeasedTask t;
    try {
      t = parse_lease(json::parse(r.body));
    } catch (const std::exception& e) {
      spdlog::error("worker: bad lease answer ({}): {}", e.what(), r.body);
      if (!backoff_sleep()) return 0;
      continue;
    }
    ++processed;

    // Small helpers bound to this lease.
    auto fail = [&](const std::string& log) {
      const HttpResponse f =
          w.http->post_json(std::string(kApi) + "/fail",
                            json{{"lease_id", t.lease_id}, {"log", tail_of(log, kLogTail)}}.dump());
      if (f.status == 409)
        spdlog::info("task {}: fail refused, lease is stale", t.id);
      else if (!f.ok())
        spdlog::warn("task {}: could not report the failure ({})", t.id, describe(f));
      ++failed_;
    };

    spdlog::info("task {} (job {}, frame {}, samples [{}, {}) of {}, attempt {}): leased", t.id,
                 t.job_id, t.frame, t.sample_begin, t.sample_end, t.spp, t.attempt);

    // 1. The scene and its assets, from the verified cache, in a task directory.
    // Downloads stream into tmp/, are hashed and renamed into place only when
    // the hash matches.
    auto fetch = [&](const std::string& blob, const fs::path& file,
                     const std::string& what) -> std::string {
      if (!is_sha256_hex(blob))
        return "the lease names a malformed " + what + " hash '" + blob + "'";
      if (sha256_file(file) == blob) return {};
      const fs::path part =
          cfg.cache_dir / "tmp" /
          (blob + "." + w.instance + "." + std::to_string(++w.render_counter) + ".part");
      const HttpResponse g = w.http->get_to_file(std::string(kApi) + "/blobs/" + blob, part);
      std::string problem;
      if (g.status != 200)
        problem = "download of " + what + " blob " + blob + " failed: " + describe(g);
      else if (const auto got = sha256_file(part); got != blob)
        problem = "downloaded " + what + " blob does not match its hash: expected " + blob +
                  ", got " + got.value_or("(unreadable)");
      else
        fs::rename(part, file, ec);
      if (problem.empty() && ec) problem = "cannot store " + file.string() + ": " + ec.message();
      fs::remove(part, ec);
      return problem;
    };
    std::string problem = fetch(t.scene, cfg.cache_dir / (t.scene + ".json"), "scene");
    for (size_t i = 0; problem.empty() && i < t.assets.size(); ++i)
      problem =
          fetch(t.assets[i].blob, worker_detail::asset_cache_file(cfg.cache_dir, t.assets[i].blob),
                "asset '" + t.assets[i].name + "'");
    fs::path task_dir;
    if (problem.empty()) {
      try {
        task_dir = worker_detail::materialise_task_dir(
            cfg.cache_dir, t.scene, t.assets,
            w.instance + "-" + std::to_string(++w.render_counter));
      } catch (const std::exception& e) {
        problem = std::string("cannot prepare the task directory: ") + e.what();
      }
    }
    if (!problem.empty()) {
      spdlog::error("task {}: {}", t.id, problem);
      fail("worker: " + problem);
      continue;
    }
    const fs::path scene_file = task_dir / "scene.json";

    // 2. Render in a child process.
    const fs::path out = cfg.cache_dir / "tmp" /
                         ("render-" + w.instance + "-" + std::to_string(++w.render_counter) +
                          (t.partial() ? ".vpartial" : ".exr"));
    std::vector<std::string> argv = {cfg.vesper_binary.string(),
                                     "render",
                                     scene_file.string(),
                                     "-o",
                                     out.string(),
                                     "--spp",
                                     std::to_string(t.spp),
                                     "--sample-begin",
                                     std::to_string(t.sample_begin),
                                     "--sample-end",
                                     std::to_string(t.sample_end),
                                     "--frame",
                                     std::to_string(t.frame)};
    if (t.partial()) argv.push_back("--partial");
    try {  // the seed the scene asks for, passed explicitly
      std::ifstream in(scene_file);
      const json scene = json::parse(in);
      if (scene.contains("render") && scene["render"].contains("seed") &&
          scene["render"]["seed"].is_number_integer()) {
        argv.push_back("--seed");
        argv.push_back(std::to_string(scene["render"]["seed"].get<long long>()));
      }
    } catch (...) {
      // Not JSON: the renderer will say so in its log.
    }
    if (cfg.render_threads > 0) {
      argv.push_back("--threads");
      argv.push_back(std::to_string(cfg.render_threads));
    }
    // Not -q: the render's plain progress lines ("render:  40% ...") on stderr
    // feed the heartbeat's progress; they also give failure logs context.
    std::string cmdline;
    for (const auto& a : argv) cmdline += (cmdline.empty() ? "" : " ") + a;

    std::unique_ptr<ChildProcess> child;
    try {
      child = std::make_unique<ChildProcess>(argv, kLogTail);
    } catch (const std::exception& e) {
      spdlog::error("task {}: {}", t.id, e.what());
      fail(std::string("worker: ") + e.what() + "\n" + cmdline);
      continue;
    }
    const auto started = Clock::now();
    const std::string duration_key = t.scene + ":" + std::to_string(t.sample_end - t.sample_begin);
    const double interval = std::max(0.05, std::min(cfg.heartbeat_seconds, t.lease_seconds / 3));
    bool dropped = false;
    while (!child->wait_for(interval)) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - started).count();
      double progress = 0.5;
      if (auto it = w.durations.find(duration_key); it != w.durations.end() && it->second > 0)
        progress = std::min(0.99, elapsed / it->second);
      if (const auto reported = worker_detail::last_render_progress(child->stderr_tail()))
        progress = *reported;
      const HttpResponse hb =
          w.http->post_json(std::string(kApi) + "/heartbeat",
                            json{{"lease_id", t.lease_id}, {"progress", progress}}.dump());
      std::string answer;
      if (hb.status == 200) {
        try {
          answer = json::parse(hb.body).at("answer").get<std::string>();
        } catch (...) {
        }
      }
      if (hb.status == 409 || answer == "stop") {
        spdlog::info("task {}: {}; killing the render", t.id,
                     hb.status == 409 ? "lease is stale" : "the server says stop");
        child->kill(cfg.kill_grace_seconds);
        dropped = true;
        break;
      }
      if (hb.status != 200) spdlog::warn("task {}: heartbeat failed ({})", t.id, describe(hb));
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
    if (dropped) {
      fs::remove(out, ec);
      ++dropped_;
      continue;
    }

    // 3a. A failed render fails the task (the worker carries on).
    if (child->exit_code() != 0 || !fs::exists(out)) {
      const std::string status =
          child->exit_code() == 0 ? "exit code 0 but no output file" : child->describe_status();
      spdlog::warn("task {}: render failed ({}) after {:.2f} s", t.id, status, seconds);
      fail("vesper render failed: " + status + "\ncommand: " + cmdline +
           "\n--- stderr (tail) ---\n" + child->stderr_tail());
      fs::remove(out, ec);
      continue;
    }
    w.durations[duration_key] = seconds;

    // 3b. Upload the result (content addressed) and complete.
    const auto result = sha256_file(out);
    bool uploaded = false;
    std::string upload_problem = "cannot read " + out.string();
    for (int tries = 0; result && tries < 3 && !uploaded; ++tries) {
      const HttpResponse p = w.http->put_file(std::string(kApi) + "/blobs/" + *result, out);
      uploaded = p.status == 200 || p.status == 201;
      if (!uploaded) {
        upload_problem = describe(p);
        spdlog::warn("task {}: upload failed ({})", t.id, upload_problem);
        std::this_thread::sleep_for(std::chrono::milliseconds(200 << tries));
      }
    }
    fs::remove(out, ec);
    if (!uploaded) {
      fail("worker: upload of the result failed: " + upload_problem);
      continue;
    }
    for (int tries = 0; tries < 3; ++tries) {
      const HttpResponse c =
          w.http->post_json(std::string(kApi) + "/complete",
                            json{{"lease_id", t.lease_id}, {"result", *result}}.dump());
      if (c.status == 200) {
        spdlog::info("task {}: done in {:.2f} s, result {}", t.id, seconds, *result);
        ++completed_;
        break;
      }
      if (c.status == 409) {  // another worker took over (lease expired) or the job was canceled
        spdlog::info("task {}: complete refused, lease is stale ({})", t.id, describe(c));
        ++dropped_;
        break;
      }
      spdlog::warn("task {}: complete failed ({})", t.id, describe(c));
      if (c.status != 0 && c.status < 500) break;  // a 4xx will not get better
      std::this_thread::sleep_for(std::chrono::milliseconds(200 << tries));
    }
  }
}

}  // namespace vesper
