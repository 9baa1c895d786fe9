// Farm dispatch: how many no-op tasks per second the job store and the HTTP
// server hand out and take back, and how long a lease takes, with many
// simulated workers looping lease -> complete (nothing is rendered).
//
//   ./build/bench/vesper_farm_bench [--tasks N] [--workers W] [--single-tasks N]
//       [--server-threads T] [--keep-alive | --connection-per-request] [--dir D] [--quick]
//
// Six runs, each on a fresh data dir: the JobStore alone with 1 and W
// threads, and a real vesper::Server on 127.0.0.1 with 1 and W httplib
// clients, first with keep-alive connections (as vesper-worker's libcurl
// handle), then with a new connection per request. Every run checks that
// each task was completed exactly once (by the workers' own tally and by the
// store or API afterwards); the program exits with 1 if any run lost or
// duplicated work.
#include <httplib.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <latch>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/sha256.h"
#include "jobs/job_store.h"
#include "server/server.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace vesper;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// What one worker thread saw.
struct WorkerLog {
  std::vector<double> lease_ms, complete_ms;        // what the caller waited
  std::vector<double> lease_in_ms, complete_in_ms;  // store runs: time holding the mutex
  std::vector<int64_t> completed;                   // task ids whose complete succeeded
  int refused = 0;                                  // complete answered false / 409
  int retries = 0;  // HTTP requests repeated after a transport error (no response)
  std::vector<std::string> errors;
};

struct Run {
  Run(std::string n, int w, int t) : name(std::move(n)), workers(w), tasks(t) {}
  std::string name;
  int workers = 0, tasks = 0;
  bool keep_alive = false;  // HTTP runs
  int retries = 0;
  double wall = 0, cores = 0;
  std::vector<double> lease_ms, complete_ms, lease_in_ms, complete_in_ms;
  std::vector<std::string> problems;  // correctness failures; empty = every task exactly once

  void merge(std::vector<WorkerLog>& logs, std::map<int64_t, int>& tally) {
    for (auto& l : logs) {
      auto append = [](std::vector<double>& to, const std::vector<double>& from) {
        to.insert(to.end(), from.begin(), from.end());
      };
      append(lease_ms, l.lease_ms);
      append(complete_ms, l.complete_ms);
      append(lease_in_ms, l.lease_in_ms);
      append(complete_in_ms, l.complete_in_ms);
      for (int64_t t : l.completed) ++tally[t];
      retries += l.retries;
      if (l.refused) problems.push_back(std::to_string(l.refused) + " completes refused");
      for (auto& e : l.errors) problems.push_back(e);
    }
  }
};

// Nearest-rank percentile (p in [0, 1]) of unsorted values.
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  size_t k = size_t(std::ceil(p * double(v.size())));
  return v[std::min(v.size() - 1, k == 0 ? 0 : k - 1)];
}

// Checks the workers' tally: `tasks` distinct tasks, each completed once.
void check_tally(const std::map<int64_t, int>& tally, int tasks, Run& run) {
  int twice = 0;
  for (const auto& [id, n] : tally)
    if (n != 1) ++twice;
  if (int(tally.size()) != tasks)
    run.problems.push_back("workers completed " + std::to_string(tally.size()) +
                           " distinct tasks, expected " + std::to_string(tasks));
  if (twice) run.problems.push_back(std::to_string(twice) + " tasks completed more than once");
}

const std::string kResult = sha256_hex("vesper farm bench: no-op result");

// --self-test-lose-one: the first task leased in each run is dropped without
// completing it, so every run must fail its check (the check can fail).
bool g_lose_one = false;

// ---- store level ----

// A fresh JobStore, one job of `tasks` one-frame tasks, `workers` threads
// looping lease -> complete. JobStore holds one SQLite connection and is not
// safe for concurrent callers, so, exactly as the server does, every call is
// made under one mutex.
Run store_run(const fs::path& dir, int tasks, int workers) {
  Run run("store", workers, tasks);
  fs::remove_all(dir);
  fs::create_directories(dir);
  StoreOptions options;
  options.lease_seconds = 3600;  // no lease may expire during the run
  JobStore store(dir / "jobs.sqlite", options);
  const auto t_origin = Clock::now();
  auto now = [&] { return 1e6 + seconds_between(t_origin, Clock::now()); };
  JobSpec spec;
  spec.name = "bench";
  spec.scene = sha256_hex("no-op scene");
  spec.spp = 1;
  for (int f = 1; f <= tasks; ++f) spec.frames.push_back(f);
  const int64_t job = store.submit(spec, now());

  std::mutex store_mutex;  // as Server::Impl::store_mutex
  std::vector<WorkerLog> logs(static_cast<size_t>(workers));
  std::atomic<bool> lost{false};  // --self-test-lose-one
  std::latch start(workers + 1);
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      WorkerLog& log = logs[static_cast<size_t>(w)];
      const std::string name = "worker-" + std::to_string(w);
      start.arrive_and_wait();
      try {
        for (;;) {
          std::optional<Lease> l;
          const auto t0 = Clock::now();
          Clock::time_point t1, t2;
          {
            std::lock_guard lock(store_mutex);
            t1 = Clock::now();
            l = store.lease(name, now());
            t2 = Clock::now();
          }
          log.lease_ms.push_back(1e3 * seconds_between(t0, t2));
          log.lease_in_ms.push_back(1e3 * seconds_between(t1, t2));
          if (!l) break;
          if (g_lose_one && !lost.exchange(true)) continue;  // lost work
          bool ok = false;
          const auto t3 = Clock::now();
          Clock::time_point t4, t5;
          {
            std::lock_guard lock(store_mutex);
            t4 = Clock::now();
            ok = store.complete(l->lease_id, kResult, now());
            t5 = Clock::now();
          }
          log.complete_ms.push_back(1e3 * seconds_between(t3, t5));
          log.complete_in_ms.push_back(1e3 * seconds_between(t4, t5));
          if (ok)
            log.completed.push_back(l->task.id);
          else
            ++log.refused;
        }
      } catch (const std::exception& e) {
        log.errors.push_back(name + ": " + e.what());
      }
    });
  const double cpu0 = cpu_seconds();
  start.arrive_and_wait();
  const auto t_start = Clock::now();
  for (auto& t : threads) t.join();
  run.wall = seconds_between(t_start, Clock::now());
  run.cores = (cpu_seconds() - cpu0) / run.wall;

  std::map<int64_t, int> tally;
  run.merge(logs, tally);
  check_tally(tally, tasks, run);
  // What the store says.
  const auto summary = store.job(job);
  if (!summary || summary->done != tasks || summary->total() != tasks)
    run.problems.push_back("store: " + std::to_string(summary ? summary->done : -1) + " of " +
                           std::to_string(summary ? summary->total() : -1) +
                           " tasks done, expected " + std::to_string(tasks));
  int wrong = 0;
  for (const Task& t : store.tasks(job))
    if (t.state != TaskState::Done || t.result != kResult || tally[t.id] != 1) ++wrong;
  if (wrong) run.problems.push_back("store: " + std::to_string(wrong) + " tasks not done once");
  return run;
}

// ---- HTTP level ----

struct HttpOptions {
  int server_threads = 16;
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

// A real Server on 127.0.0.1 (ephemeral port, fresh data dir) and `workers`
// httplib clients, each registering once and then looping lease -> complete
// with one pre-uploaded result blob. Latency is the client-side round trip.
Run http_run(const fs::path& dir, int tasks, int workers, const HttpOptions& o, bool keep_alive) {
  Run run("HTTP", workers, tasks);
  run.keep_alive = keep_alive;
  fs::remove_all(dir);
  ServerConfig config;
  config.data_dir = dir;
  config.lease_seconds = 3600;  // no lease may expire during the run
  config.threads = o.server_threads;
  Server server(config);
  const int port = server.start();
  const auto sub = bearer(server.submitter_token()), wrk = bearer(server.worker_token());

  httplib::Client admin("127.0.0.1", port);
  admin.set_read_timeout(60);
  auto put_blob = [&](const std::string& bytes) {
    const std::string h = sha256_hex(bytes);
    auto r = admin.Put(("/api/v1/blobs/" + h).c_str(), wrk, bytes, "application/octet-stream");
    if (!r || (r->status != 200 && r->status != 201))
      throw std::runtime_error("blob upload failed: " + (r ? r->body : to_string(r.error())));
    return h;
  };
  const std::string scene = put_blob("{\"format\": \"vesper-scene/1\"}");
  if (put_blob("vesper farm bench: no-op result") != kResult) throw std::logic_error("hash");
  auto r = admin.Post(
      "/api/v1/jobs", sub,
      json{
          {"name", "bench"}, {"scene", scene}, {"frames", "1-" + std::to_string(tasks)}, {"spp", 1}}
          .dump(),
      "application/json");
  if (!r || r->status != 201)
    throw std::runtime_error("submit failed: " + (r ? r->body : to_string(r.error())));
  const int64_t job = json::parse(r->body).at("id").get<int64_t>();

  std::vector<WorkerLog> logs(static_cast<size_t>(workers));
  std::atomic<bool> lost{false};  // --self-test-lose-one
  std::latch start(workers + 1);
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      WorkerLog& log = logs[static_cast<size_t>(w)];
      const std::string name = "worker-" + std::to_string(w);
      httplib::Client c("127.0.0.1", port);
      c.set_keep_alive(keep_alive);
      c.set_tcp_nodelay(true);  // as libcurl (vesper-worker) does by default
      c.set_read_timeout(60);
      std::string id;
      try {
        auto reg = with_retries(log, "register", [&] {
          return c.Post("/api/v1/workers/register", wrk, json{{"name", name}}.dump(),
                        "application/json");
        });
        if (reg->status != 200) throw std::runtime_error("register: " + reg->body);
        id = json::parse(reg->body).at("worker_id").get<std::string>();
      } catch (const std::exception& e) {
        log.errors.push_back(name + ": " + e.what());
      }
      // Close the registration's connection before waiting: an idle keep-alive
      // connection holds a server thread until the server's keep-alive timeout
      // (5 s), and 50 idle workers would starve the other registrations.
      c.stop();
      start.arrive_and_wait();
      if (id.empty()) return;
      const std::string lease_body = json{{"worker_id", id}}.dump();
      try {
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
          const std::string body =
              json{{"lease_id", lj.at("lease_id")}, {"result", kResult}}.dump();
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
      } catch (const std::exception& e) {
        log.errors.push_back(name + ": " + e.what());
      }
    });
  const double cpu0 = cpu_seconds();
  start.arrive_and_wait();
  const auto t_start = Clock::now();
  for (auto& t : threads) t.join();
  run.wall = seconds_between(t_start, Clock::now());
  run.cores = (cpu_seconds() - cpu0) / run.wall;  // clients and server: one process

  std::map<int64_t, int> tally;
  run.merge(logs, tally);
  check_tally(tally, tasks, run);
  // What the API says.
  r = admin.Get(("/api/v1/jobs/" + std::to_string(job)).c_str(), sub);
  if (!r || r->status != 200) {
    run.problems.push_back("GET /jobs/" + std::to_string(job) + " failed");
  } else {
    const json j = json::parse(r->body);
    const int done = j.at("counts").at("done").get<int>(), total = j.at("total").get<int>();
    if (done != tasks || total != tasks)
      run.problems.push_back("API: " + std::to_string(done) + " of " + std::to_string(total) +
                             " tasks done, expected " + std::to_string(tasks));
    int wrong = 0;
    for (const json& t : j.at("tasks"))
      if (t.at("state") != "done" || t.at("result") != kResult ||
          tally[t.at("id").get<int64_t>()] != 1)
        ++wrong;
    if (wrong) run.problems.push_back("API: " + std::to_string(wrong) + " tasks not done once");
  }
  server.stop();
  return run;
}

void print_header() {
  std::printf("  %-34s %7s %6s %8s %8s %5s | %21s | %21s\n", "", "workers", "tasks", "wall [s]",
              "tasks/s", "cores", "lease p50/p99/max [ms]", "complete p50/p99/max");
}

void print_row(const Run& r, const char* label, const std::vector<double>& lease,
               const std::vector<double>& complete, bool rate) {
  char rate_s[16] = "", wall_s[16] = "", cores_s[16] = "";
  if (rate) {
    std::snprintf(wall_s, sizeof wall_s, "%.2f", r.wall);
    std::snprintf(rate_s, sizeof rate_s, "%.0f", r.tasks / r.wall);
    std::snprintf(cores_s, sizeof cores_s, "%.2f", r.cores);
  }
  std::printf("  %-34s %7d %6d %8s %8s %5s | %6.2f %6.2f %7.1f | %6.2f %6.2f %7.1f\n", label,
              r.workers, r.tasks, wall_s, rate_s, cores_s, percentile(lease, 0.5),
              percentile(lease, 0.99), percentile(lease, 1.0), percentile(complete, 0.5),
              percentile(complete, 0.99), percentile(complete, 1.0));
}

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s [--tasks N (1000)] [--workers W (50)] [--single-tasks N (200)]\n"
               "          [--server-threads T (16)] [--keep-alive | --connection-per-request]\n"
               "          [--dir DIR] [--quick]\n",
               argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int tasks = 1000, workers = 50, single_tasks = 200;
  HttpOptions http;
  fs::path base = fs::temp_directory_path();
  bool quick = std::getenv("VESPER_BENCH_QUICK") != nullptr;
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
      quick = true;
    } else if (a == "--self-test-lose-one") {
      g_lose_one = true;
    } else if (a == "--keep-alive") {
      http.connections = HttpOptions::Connections::KeepAlive;
    } else if (a == "--connection-per-request") {
      http.connections = HttpOptions::Connections::PerRequest;
    } else if (a == "--dir") {
      const char* v = value();
      if (!v) return usage(argv[0]);
      base = v;
    } else if (!((a == "--tasks" && int_value(tasks)) || (a == "--workers" && int_value(workers)) ||
                 (a == "--single-tasks" && int_value(single_tasks)) ||
                 (a == "--server-threads" && int_value(http.server_threads)))) {
      return usage(argv[0]);
    }
  }
  if (quick) {
    tasks = std::min(tasks, 300);
    single_tasks = std::min(single_tasks, 50);
  }
  // The server logs every registration (info) and that it cannot merge
  // sample ranges without a vesper binary next to it (warning; no task here
  // has several sample ranges).
  spdlog::set_level(spdlog::level::err);

  const fs::path dir = base / ("vesper-farm-bench-" + std::to_string(::getpid()));
  std::vector<Run> runs;
  int status = 0;
  try {
    runs.push_back(store_run(dir / "store-1", single_tasks, 1));
    runs.push_back(store_run(dir / "store-n", tasks, workers));
    for (bool keep_alive : {true, false}) {
      using C = HttpOptions::Connections;
      if (http.connections == (keep_alive ? C::PerRequest : C::KeepAlive)) continue;
      const std::string k = keep_alive ? "-ka" : "-close";
      runs.push_back(http_run(dir / ("http-1" + k), single_tasks, 1, http, keep_alive));
      runs.push_back(http_run(dir / ("http-n" + k), tasks, workers, http, keep_alive));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    status = 1;
  }
  fs::remove_all(dir);

  std::printf(
      "farm dispatch: no-op tasks (lease -> complete, nothing rendered), one job of one-frame "
      "tasks,\nSQLite WAL store (synchronous = FULL) under %s; %u hardware threads\n",
      base.c_str(), std::thread::hardware_concurrency());
  std::printf(
      "HTTP: vesper::Server on 127.0.0.1, %d server threads; one httplib::Client per worker,\n"
      "either keep-alive (like vesper-worker's libcurl handle) or a new connection per request\n\n",
      http.server_threads);
  print_header();
  for (const Run& r : runs) {
    if (r.name == "store") {
      print_row(r, "JobStore + mutex (caller's wait)", r.lease_ms, r.complete_ms, true);
      print_row(r, "  inside the mutex (the call)", r.lease_in_ms, r.complete_in_ms, false);
    } else {
      print_row(
          r, r.keep_alive ? "HTTP keep-alive (round trip)" : "HTTP conn. per request (round trip)",
          r.lease_ms, r.complete_ms, true);
    }
  }
  // The last lease of each worker (the one that finds no work) is in the
  // latencies but is not a task.
  std::printf("\n");
  for (const Run& r : runs) {
    const std::string name =
        r.name == "store" ? "store" : (r.keep_alive ? "HTTP keep-alive" : "HTTP per request");
    const std::string retried =
        r.retries ? ", " + std::to_string(r.retries) + " requests repeated after no response" : "";
    if (r.problems.empty()) {
      std::printf("  check %-16s %3d workers: all %d tasks completed exactly once%s\n",
                  name.c_str(), r.workers, r.tasks, retried.c_str());
      continue;
    }
    status = 1;
    std::printf("  CHECK FAILED %s, %d workers%s:\n", name.c_str(), r.workers, retried.c_str());
    size_t shown = 0;
    for (const auto& p : r.problems)
      if (shown++ < 10) std::printf("    %s\n", p.c_str());
  }
  return status;
}
