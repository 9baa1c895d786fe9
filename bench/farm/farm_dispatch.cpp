// Farm dispatch: how many no-op tasks per second the job store and the HTTP
// server hand out and take back, and how long a lease takes, with many
// simulated workers looping lease -> complete (nothing is rendered).
//
//   ./build/bench/vesper_farm_bench [--tasks N] [--workers W] [--single-tasks N]
//       [--server-threads T] [--keep-alive | --connection-per-request] [--dir D] [--quick]
//       [--monitor-pages P] [--monitor-interval S]
//
// Six runs, each on a fresh data dir: the JobStore alone with 1 and W
// threads, and a real vesper::Server on 127.0.0.1 with 1 and W httplib
// clients, first with keep-alive connections (as vesper-worker's libcurl
// handle), then with a new connection per request. Every run checks that
// each task was completed exactly once (by the workers' own tally and by the
// store or API afterwards); the program exits with 1 if any run lost or
// duplicated work. With --monitor-pages P (5) > 0, the keep-alive run with W
// workers is repeated with P open monitor pages polling every S (2) seconds
// (monitor_pages.h), so the two rows show what the pages cost.
#include <httplib.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/farm/dispatch_run.h"
#include "bench/farm/monitor_pages.h"
#include "common/sha256.h"
#include "jobs/job_store.h"
#include "server/server.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace vesper;
using namespace vesper::farm_bench;

namespace {

const std::string kResult = sha256_hex("vesper farm bench: no-op result");

// --self-test-lose-one: the first task leased in each run is dropped without
// completing it, so every run must fail its check (the check can fail).
bool g_lose_one = false;

// ---- store level ----

// `call()` under `mutex`, recording how long the caller waited in total and
// how long it held the mutex.
template <class F>
auto call_locked(std::mutex& mutex, std::vector<double>& waited_ms, std::vector<double>& inside_ms,
                 F call) {
  const auto t0 = Clock::now();
  std::lock_guard lock(mutex);
  const auto t1 = Clock::now();
  auto result = call();
  const auto t2 = Clock::now();
  waited_ms.push_back(1e3 * seconds_between(t0, t2));
  inside_ms.push_back(1e3 * seconds_between(t1, t2));
  return result;
}

// The store-level load: one job of `tasks` one-frame tasks, and workers that
// lease and complete them. JobStore holds one SQLite connection and is not
// safe for concurrent callers, so, exactly as the server does, every call is
// made under one mutex.
struct StoreLoad {
  StoreLoad(JobStore& s, std::function<double()> clock) : store(s), now(std::move(clock)) {}
  JobStore& store;
  std::function<double()> now;
  std::mutex store_mutex;         // as Server::Impl::store_mutex
  std::atomic<bool> lost{false};  // --self-test-lose-one

  int64_t submit(int tasks) {
    JobSpec spec;
    spec.name = "bench";
    spec.scene = sha256_hex("no-op scene");
    spec.spp = 1;
    for (int f = 1; f <= tasks; ++f) spec.frames.push_back(f);
    return store.submit(spec, now());
  }

  // One worker looping lease -> complete until no task is left.
  void work(const std::string& name, WorkerLog& log) {
    for (;;) {
      const auto l = call_locked(store_mutex, log.lease_ms, log.lease_in_ms,
                                 [&] { return store.lease(name, now()); });
      if (!l) break;
      if (g_lose_one && !lost.exchange(true)) continue;  // lost work
      if (call_locked(store_mutex, log.complete_ms, log.complete_in_ms,
                      [&] { return store.complete(l->lease_id, kResult, now()); }))
        log.completed.push_back(l->task.id);
      else
        ++log.refused;
    }
  }

  // What the store says: every task of `job` done once, with the result.
  void check(int64_t job, std::map<int64_t, int>& tally, Run& run) const {
    const auto summary = store.job(job);
    if (!summary || summary->done != run.tasks || summary->total() != run.tasks)
      run.problems.push_back("store: " + std::to_string(summary ? summary->done : -1) + " of " +
                             std::to_string(summary ? summary->total() : -1) +
                             " tasks done, expected " + std::to_string(run.tasks));
    int wrong = 0;
    for (const Task& t : store.tasks(job))
      if (t.state != TaskState::Done || t.result != kResult || tally[t.id] != 1) ++wrong;
    if (wrong) run.problems.push_back("store: " + std::to_string(wrong) + " tasks not done once");
  }
};

// A fresh JobStore, one job of `tasks` one-frame tasks, `workers` threads
// looping lease -> complete.
Run store_run(const fs::path& dir, int tasks, int workers) {
  Run run("store", workers, tasks);
  fs::remove_all(dir);
  fs::create_directories(dir);
  StoreOptions options;
  options.lease_seconds = 3600;  // no lease may expire during the run
  JobStore store(dir / "jobs.sqlite", options);
  const auto t_origin = Clock::now();
  StoreLoad load(store, [t_origin] { return 1e6 + seconds_between(t_origin, Clock::now()); });
  const int64_t job = load.submit(tasks);
  auto tally = run_workers(run, [&](int w, WorkerLog& log, auto ready) {
    const std::string name = "worker-" + std::to_string(w);
    ready();
    try {
      load.work(name, log);
    } catch (const std::exception& e) {
      log.errors.push_back(name + ": " + e.what());
    }
  });
  load.check(job, tally, run);
  return run;
}

// ---- HTTP level ----

struct HttpOptions {
  int server_threads = 16;
  int monitor_pages = 5;          // the extra run's open monitor pages (0: no such run)
  double monitor_interval = 2.0;  // seconds between a page's polls (monitor.js)
  enum class Connections { Both, KeepAlive, PerRequest } connections = Connections::Both;
};

// A request that got no response at all (connection refused, reset, timed
// out) is sent again, as vesper-worker does, up to 20 times. The resets seen
// here come from connections the server never accepted, so the first request
// was not processed; were it processed, a repeated lease would leave its
// first task leased and a repeated complete would get a 409: both fail the
// exactly-once check below.
template <class F>
httplib::Result with_retries(WorkerLog& log, const char* what, F request) {
  for (int attempt = 0;; ++attempt) {
    auto r = request();
    if (r) return r;
    if (attempt == 20)
      throw std::runtime_error(std::string(what) + ": " + to_string(r.error()) + " (" +
                               std::to_string(attempt + 1) + " attempts)");
    ++log.retries;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

httplib::Headers bearer(const std::string& token) { return {{"Authorization", "Bearer " + token}}; }

// The HTTP-level load: a real Server's API, one job of `tasks` one-frame
// tasks submitted through it, and httplib clients as workers.
struct HttpLoad {
  int port = 0;
  httplib::Headers sub, wrk;
  bool keep_alive = true;
  std::atomic<bool> lost{false};  // --self-test-lose-one

  // Uploads the scene and the one result blob, submits the job; returns its id.
  int64_t submit(httplib::Client& admin, int tasks) const {
    auto put_blob = [&](const std::string& bytes) {
      const std::string h = sha256_hex(bytes);
      auto r = admin.Put(("/api/v1/blobs/" + h).c_str(), wrk, bytes, "application/octet-stream");
      if (!r || (r->status != 200 && r->status != 201))
        throw std::runtime_error("blob upload failed: " + (r ? r->body : to_string(r.error())));
      return h;
    };
    const std::string scene = put_blob("{\"format\": \"vesper-scene/1\"}");
    if (put_blob("vesper farm bench: no-op result") != kResult) throw std::logic_error("hash");
    const json job = {
        {"name", "bench"}, {"scene", scene}, {"frames", "1-" + std::to_string(tasks)}, {"spp", 1}};
    auto r = admin.Post("/api/v1/jobs", sub, job.dump(), "application/json");
    if (!r || r->status != 201)
      throw std::runtime_error("submit failed: " + (r ? r->body : to_string(r.error())));
    return json::parse(r->body).at("id").get<int64_t>();
  }

  // Registers `name`; returns its worker id.
  std::string register_worker(httplib::Client& c, const std::string& name, WorkerLog& log) const {
    auto reg = with_retries(log, "register", [&] {
      return c.Post("/api/v1/workers/register", wrk, json{{"name", name}}.dump(),
                    "application/json");
    });
    if (reg->status != 200) throw std::runtime_error("register: " + reg->body);
    return json::parse(reg->body).at("worker_id").get<std::string>();
  }

  // Loops lease -> complete until the server has no task left.
  void work(httplib::Client& c, const std::string& id, WorkerLog& log) {
    const std::string lease_body = json{{"worker_id", id}}.dump();
    for (;;) {
      const auto t0 = Clock::now();
      auto l = with_retries(log, "lease", [&] {
        return c.Post("/api/v1/lease", wrk, lease_body, "application/json");
      });
      log.lease_ms.push_back(1e3 * seconds_between(t0, Clock::now()));
      if (l->status == 204) break;
      if (l->status != 200)
        throw std::runtime_error("lease: " + std::to_string(l->status) + " " + l->body);
      const json lj = json::parse(l->body);
      const int64_t task = lj.at("task").at("id").get<int64_t>();
      if (g_lose_one && !lost.exchange(true)) continue;  // lost work
      const std::string body = json{{"lease_id", lj.at("lease_id")}, {"result", kResult}}.dump();
      const auto t1 = Clock::now();
      auto d = with_retries(log, "complete", [&] {
        return c.Post("/api/v1/complete", wrk, body, "application/json");
      });
      log.complete_ms.push_back(1e3 * seconds_between(t1, Clock::now()));
      if (d->status == 200)
        log.completed.push_back(task);
      else if (d->status == 409)
        ++log.refused;
      else
        throw std::runtime_error("complete: " + std::to_string(d->status) + " " + d->body);
    }
  }

  // One worker thread: registers, waits for the start, then works.
  void worker(int w, WorkerLog& log, const std::function<void()>& ready) {
    const std::string name = "worker-" + std::to_string(w);
    httplib::Client c("127.0.0.1", port);
    c.set_keep_alive(keep_alive);
    c.set_tcp_nodelay(true);  // as libcurl (vesper-worker) does by default
    c.set_read_timeout(60);
    std::string id;
    try {
      id = register_worker(c, name, log);
    } catch (const std::exception& e) {
      log.errors.push_back(name + ": " + e.what());
    }
    // Close the registration's connection before waiting: an idle keep-alive
    // connection holds a server thread until the server's keep-alive timeout
    // (5 s), and 50 idle workers would starve the other registrations.
    c.stop();
    ready();
    if (id.empty()) return;
    try {
      work(c, id, log);
    } catch (const std::exception& e) {
      log.errors.push_back(name + ": " + e.what());
    }
  }

  // What the API says: every task of `job` done once, with the result.
  void check(httplib::Client& admin, int64_t job, std::map<int64_t, int>& tally, Run& run) const {
    auto r = admin.Get(("/api/v1/jobs/" + std::to_string(job)).c_str(), sub);
    if (!r || r->status != 200) {
      run.problems.push_back("GET /jobs/" + std::to_string(job) + " failed");
      return;
    }
    const json j = json::parse(r->body);
    const int done = j.at("counts").at("done").get<int>(), total = j.at("total").get<int>();
    if (done != run.tasks || total != run.tasks)
      run.problems.push_back("API: " + std::to_string(done) + " of " + std::to_string(total) +
                             " tasks done, expected " + std::to_string(run.tasks));
    int wrong = 0;
    for (const json& t : j.at("tasks"))
      if (t.at("state") != "done" || t.at("result") != kResult ||
          tally[t.at("id").get<int64_t>()] != 1)
        ++wrong;
    if (wrong) run.problems.push_back("API: " + std::to_string(wrong) + " tasks not done once");
  }
};

// A real Server on 127.0.0.1 (ephemeral port, fresh data dir) and `workers`
// httplib clients, each registering once and then looping lease -> complete
// with one pre-uploaded result blob. Latency is the client-side round trip.
Run http_run(const fs::path& dir, int tasks, int workers, const HttpOptions& o, bool keep_alive,
             int monitor_pages = 0) {
  Run run("HTTP", workers, tasks);
  run.keep_alive = keep_alive;
  run.monitor_pages = monitor_pages;
  fs::remove_all(dir);
  ServerConfig config;
  config.data_dir = dir;
  config.lease_seconds = 3600;  // no lease may expire during the run
  config.threads = o.server_threads;
  // The one result blob is made-up bytes on purpose (dispatch, not results, is
  // measured here); vesper_verify_bench measures the check's cost.
  config.verify_results = false;
  Server server(config);
  HttpLoad load;
  load.port = server.start();
  load.sub = bearer(server.submitter_token());
  load.wrk = bearer(server.worker_token());
  load.keep_alive = keep_alive;
  httplib::Client admin("127.0.0.1", load.port);
  admin.set_read_timeout(60);
  const int64_t job = load.submit(admin, tasks);
  std::optional<MonitorPages> pages;
  if (monitor_pages > 0)
    pages.emplace(load.port, server.submitter_token(), monitor_pages, o.monitor_interval, job);
  auto tally =
      run_workers(run, [&](int w, WorkerLog& log, auto ready) { load.worker(w, log, ready); });
  if (pages) {
    pages->stop();
    run.monitor_requests = pages->requests();
    if (pages->failures())
      run.problems.push_back(std::to_string(pages->failures()) + " monitor requests failed");
  }
  load.check(admin, job, tally, run);
  server.stop();
  return run;
}

int usage(const char* argv0) {
  std::fprintf(
      stderr,
      "usage: %s [--tasks N (1000)] [--workers W (50)] [--single-tasks N (200)]\n"
      "          [--server-threads T (16)] [--keep-alive | --connection-per-request]\n"
      "          [--dir DIR] [--quick] [--monitor-pages P (5)] [--monitor-interval S (2)]\n",
      argv0);
  return 2;
}

struct Options {
  int tasks = 1000, workers = 50, single_tasks = 200;
  HttpOptions http;
  fs::path base = fs::temp_directory_path();
  bool quick = std::getenv("VESPER_BENCH_QUICK") != nullptr;
};

// The command line, or nothing on a usage error.
std::optional<Options> parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    auto int_value = [&](int& out) {
      const char* v = value();
      if (!v || std::atoi(v) < 1) return false;
      out = std::atoi(v);
      return true;
    };
    if (a == "--quick") {
      o.quick = true;
    } else if (a == "--self-test-lose-one") {
      g_lose_one = true;
    } else if (a == "--keep-alive") {
      o.http.connections = HttpOptions::Connections::KeepAlive;
    } else if (a == "--connection-per-request") {
      o.http.connections = HttpOptions::Connections::PerRequest;
    } else if (a == "--monitor-pages" || a == "--monitor-interval") {
      const char* v = value();
      if (!v) return std::nullopt;
      if (a == "--monitor-pages")
        o.http.monitor_pages = std::atoi(v);
      else
        o.http.monitor_interval = std::atof(v);
      if (o.http.monitor_pages < 0 || !(o.http.monitor_interval > 0)) return std::nullopt;
    } else if (a == "--dir") {
      const char* v = value();
      if (!v) return std::nullopt;
      o.base = v;
    } else if (!((a == "--tasks" && int_value(o.tasks)) ||
                 (a == "--workers" && int_value(o.workers)) ||
                 (a == "--single-tasks" && int_value(o.single_tasks)) ||
                 (a == "--server-threads" && int_value(o.http.server_threads)))) {
      return std::nullopt;
    }
  }
  if (o.quick) {
    o.tasks = std::min(o.tasks, 300);
    o.single_tasks = std::min(o.single_tasks, 50);
  }
  return o;
}

// Every run, each on a fresh data dir under `dir`; returns 1 if one could not
// be set up (the runs before it are kept).
int run_all(const Options& o, const fs::path& dir, std::vector<Run>& runs) {
  try {
    runs.push_back(store_run(dir / "store-1", o.single_tasks, 1));
    runs.push_back(store_run(dir / "store-n", o.tasks, o.workers));
    for (bool keep_alive : {true, false}) {
      using C = HttpOptions::Connections;
      if (o.http.connections == (keep_alive ? C::PerRequest : C::KeepAlive)) continue;
      const std::string k = keep_alive ? "-ka" : "-close";
      runs.push_back(http_run(dir / ("http-1" + k), o.single_tasks, 1, o.http, keep_alive));
      runs.push_back(http_run(dir / ("http-n" + k), o.tasks, o.workers, o.http, keep_alive));
      if (keep_alive && o.http.monitor_pages > 0)
        runs.push_back(http_run(dir / "http-n-monitor", o.tasks, o.workers, o.http, true,
                                o.http.monitor_pages));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}

void print_table(const Options& o, const std::vector<Run>& runs) {
  std::printf(
      "farm dispatch: no-op tasks (lease -> complete, nothing rendered), one job of one-frame "
      "tasks,\nSQLite WAL store (synchronous = FULL) under %s; %u hardware threads\n",
      o.base.c_str(), std::thread::hardware_concurrency());
  std::printf(
      "HTTP: vesper::Server on 127.0.0.1, %d server threads; one httplib::Client per worker,\n"
      "either keep-alive (like vesper-worker's libcurl handle) or a new connection per request\n\n",
      o.http.server_threads);
  print_header();
  for (const Run& r : runs) {
    if (r.name == "store") {
      print_row(r, "JobStore + mutex (caller's wait)", r.lease_ms, r.complete_ms, true);
      print_row(r, "  inside the mutex (the call)", r.lease_in_ms, r.complete_in_ms, false);
    } else if (r.monitor_pages > 0) {
      const std::string label = "  + " + std::to_string(r.monitor_pages) + " monitor pages";
      print_row(r, label.c_str(), r.lease_ms, r.complete_ms, true);
    } else {
      print_row(
          r, r.keep_alive ? "HTTP keep-alive (round trip)" : "HTTP conn. per request (round trip)",
          r.lease_ms, r.complete_ms, true);
    }
  }
  for (const Run& r : runs)
    if (r.monitor_pages > 0)
      std::printf(
          "\n%d monitor pages (login cookie; jobs + workers + the job's first 500 tasks "
          "every %.1f s) made %lld requests in %.2f s (%.1f/s)\n",
          r.monitor_pages, o.http.monitor_interval, (long long)r.monitor_requests, r.wall,
          double(r.monitor_requests) / r.wall);
  // The last lease of each worker (the one that finds no work) is in the
  // latencies but is not a task.
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const auto options = parse_options(argc, argv);
  if (!options) return usage(argv[0]);
  // The server logs every registration (info) and that it cannot merge
  // sample ranges without a vesper binary next to it (warning; no task here
  // has several sample ranges).
  spdlog::set_level(spdlog::level::err);

  const fs::path dir = options->base / ("vesper-farm-bench-" + std::to_string(::getpid()));
  std::vector<Run> runs;
  const int setup_failed = run_all(*options, dir, runs);
  fs::remove_all(dir);
  print_table(*options, runs);
  const int check_failed = print_checks(runs);
  return setup_failed || check_failed ? 1 : 0;
}
