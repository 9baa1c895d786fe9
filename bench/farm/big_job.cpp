// Big jobs: what one job of very many tasks costs every other call. A real
// vesper::Server on 127.0.0.1 gets one job of N one-frame tasks (100 000, the
// API's limit, by default); then one worker leases and completes K of them,
// first alone, then while a second client reads the job (GET /jobs/{id},
// every page of its task list) in a loop. Nothing is rendered.
//
//   ./build/bench/vesper_bigjob_bench [--tasks N (100000)] [--leases K (1000)] [--dir D] [--quick]
//
// Reported: submit time; leases/s and lease latency (p50/p99/max, client
// round trip) alone and beside the reader; how long one full read of the job
// takes. The program exits 1 if a lease or complete fails or the job's task
// list does not hold N tasks with exactly the K completed ones done.
#include <httplib.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "bench/farm/dispatch_run.h"
#include "common/sha256.h"
#include "server/server.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace vesper;
using namespace vesper::farm_bench;

namespace {

const std::string kResult = sha256_hex("vesper big-job bench: no-op result");

struct Options {
  int tasks = 100000, leases = 1000;
  fs::path base = fs::temp_directory_path();
};

httplib::Headers bearer(const std::string& token) { return {{"Authorization", "Bearer " + token}}; }

struct Api {
  httplib::Client& c;
  httplib::Headers sub, wrk;

  json post(const std::string& path, const httplib::Headers& h, const json& body, int want) {
    auto r = c.Post(("/api/v1" + path).c_str(), h, body.dump(), "application/json");
    if (!r || r->status != want)
      throw std::runtime_error(
          "POST " + path + ": " +
          (r ? std::to_string(r->status) + " " + r->body : to_string(r.error())));
    return r->body.empty() ? json() : json::parse(r->body);
  }
  void put_blob(const std::string& bytes) {
    auto r = c.Put(("/api/v1/blobs/" + sha256_hex(bytes)).c_str(), wrk, bytes,
                   "application/octet-stream");
    if (!r || (r->status != 200 && r->status != 201)) throw std::runtime_error("blob upload");
  }
  // Every task of the job, following the task list's pages when it has them.
  std::vector<json> job_tasks(int64_t job) {
    std::vector<json> tasks;
    std::string query;
    for (;;) {
      auto r = c.Get(("/api/v1/jobs/" + std::to_string(job) + query).c_str(), sub);
      if (!r || r->status != 200) throw std::runtime_error("GET /jobs/" + std::to_string(job));
      const json j = json::parse(r->body);
      for (const json& t : j.at("tasks")) tasks.push_back(t);
      if (!j.contains("tasks_next")) return tasks;
      query = "?tasks_after=" + std::to_string(j.at("tasks_next").get<int64_t>());
    }
  }
};

struct Phase {
  std::string name;
  double wall = 0;
  std::vector<double> lease_ms;
};

// One worker leasing and completing `leases` tasks.
Phase lease_loop(Api& api, const std::string& worker_id, int leases, const char* name,
                 std::set<int64_t>& completed) {
  Phase p{name, 0, {}};
  const auto t0 = Clock::now();
  for (int i = 0; i < leases; ++i) {
    const auto a = Clock::now();
    const json l = api.post("/lease", api.wrk, {{"worker_id", worker_id}}, 200);
    p.lease_ms.push_back(1e3 * seconds_between(a, Clock::now()));
    api.post("/complete", api.wrk, {{"lease_id", l.at("lease_id")}, {"result", kResult}}, 200);
    completed.insert(l.at("task").at("id").get<int64_t>());
  }
  p.wall = seconds_between(t0, Clock::now());
  return p;
}

void print_phase(const Phase& p) {
  std::printf("%-34s %8.1f %9.2f %9.2f %9.2f\n", p.name.c_str(), double(p.lease_ms.size()) / p.wall,
              percentile(p.lease_ms, 0.5), percentile(p.lease_ms, 0.99),
              percentile(p.lease_ms, 1.0));
}

struct Reads {
  Phase phase;
  std::vector<double> ms;  // each full read of the job
  std::string error;
};

// The second phase: full reads of the job, back to back on their own
// connection, while the worker leases.
Reads lease_while_read(Api& api, httplib::Client& reader_client, int64_t job,
                       const std::string& worker, int leases, std::set<int64_t>& completed) {
  Reads out;
  std::atomic<bool> stop{false};
  std::thread reader([&] {
    Api r{reader_client, api.sub, api.wrk};
    try {
      while (!stop) {
        const auto a = Clock::now();
        r.job_tasks(job);
        out.ms.push_back(1e3 * seconds_between(a, Clock::now()));
      }
    } catch (const std::exception& e) {
      out.error = e.what();
    }
  });
  out.phase = lease_loop(api, worker, leases, "lease + complete, job being read", completed);
  stop = true;
  reader.join();
  return out;
}

int run(const Options& o, const fs::path& dir) {
  ServerConfig config;
  config.data_dir = dir;
  config.lease_seconds = 3600;
  config.verify_results = false;  // the results are placeholder bytes, not renders
  Server server(config);
  const int port = server.start();
  httplib::Client c("127.0.0.1", port), reader_client("127.0.0.1", port);
  for (auto* cl : {&c, &reader_client}) cl->set_read_timeout(300);
  Api api{c, bearer(server.submitter_token()), bearer(server.worker_token())};
  const std::string scene = "{\"format\": \"vesper-scene/1\"}";
  api.put_blob(scene);
  api.put_blob("vesper big-job bench: no-op result");

  const auto t0 = Clock::now();
  const int64_t job = api.post("/jobs", api.sub,
                               {{"name", "big"},
                                {"scene", sha256_hex(scene)},
                                {"frames", "1-" + std::to_string(o.tasks)},
                                {"spp", 1}},
                               201)
                          .at("id");
  const double submit_s = seconds_between(t0, Clock::now());
  const std::string worker =
      api.post("/workers/register", api.wrk, {{"name", "bench"}}, 200).at("worker_id");

  std::set<int64_t> completed;
  std::vector<Phase> phases;
  phases.push_back(lease_loop(api, worker, o.leases, "lease + complete, alone", completed));

  Reads reads = lease_while_read(api, reader_client, job, worker, o.leases, completed);
  phases.push_back(std::move(reads.phase));
  const std::vector<double>& read_ms = reads.ms;
  const std::string& reader_error = reads.error;

  // The check: N tasks, exactly the completed ones done.
  const std::vector<json> tasks = api.job_tasks(job);
  int wrong = 0;
  for (const json& t : tasks)
    wrong += (t.at("state") == "done") != completed.count(t.at("id").get<int64_t>());
  server.stop();

  std::printf(
      "big job: one job of %d one-frame tasks on a real server (127.0.0.1, data dir under %s);\n"
      "one worker leases and completes %d tasks per phase (client round trips); nothing "
      "rendered\n\n",
      o.tasks, o.base.c_str(), o.leases);
  std::printf("submit: %.2f s\n\n", submit_s);
  std::printf("%-34s %8s %9s %9s %9s\n", "phase", "leases/s", "p50 [ms]", "p99 [ms]", "max [ms]");
  for (const Phase& p : phases) print_phase(p);
  if (!read_ms.empty())
    std::printf(
        "\nfull read of the job (GET /jobs/%lld, every page): %zu reads, p50 %.0f ms, max "
        "%.0f ms\n",
        static_cast<long long>(job), read_ms.size(), percentile(read_ms, 0.5),
        percentile(read_ms, 1.0));
  int problems = 0;
  if (!reader_error.empty()) {
    std::printf("CHECK FAILED: reader: %s\n", reader_error.c_str());
    ++problems;
  }
  if (int(tasks.size()) != o.tasks || wrong != 0 || int(completed.size()) != 2 * o.leases) {
    std::printf(
        "CHECK FAILED: %zu tasks listed (expected %d), %d in the wrong state, %zu completed\n",
        tasks.size(), o.tasks, wrong, completed.size());
    ++problems;
  }
  if (!problems)
    std::printf("\ncheck: %d tasks listed, exactly the %zu completed ones done\n", o.tasks,
                completed.size());
  return problems ? 1 : 0;
}

std::optional<Options> parse(int argc, char** argv) {
  Options o;
  if (std::getenv("VESPER_BENCH_QUICK")) o = {3000, 50, o.base};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "--quick") {
      o.tasks = 3000;
      o.leases = 50;
    } else if (v && a == "--tasks" && std::atoi(v) > 0) {
      o.tasks = std::atoi(argv[++i]);
    } else if (v && a == "--leases" && std::atoi(v) > 0) {
      o.leases = std::atoi(argv[++i]);
    } else if (v && a == "--dir") {
      o.base = argv[++i];
    } else {
      return std::nullopt;
    }
  }
  if (2 * o.leases > o.tasks) return std::nullopt;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const auto o = parse(argc, argv);
  if (!o) {
    std::fprintf(stderr,
                 "usage: %s [--tasks N (100000)] [--leases K (1000), 2K <= N] [--dir DIR] "
                 "[--quick]\n",
                 argv[0]);
    return 2;
  }
  spdlog::set_level(spdlog::level::err);
  const fs::path dir = o->base / ("vesper-bigjob-bench-" + std::to_string(::getpid()));
  int rc = 1;
  try {
    rc = run(*o, dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
  fs::remove_all(dir);
  return rc;
}
