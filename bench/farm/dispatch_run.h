#pragma once
// What one farm dispatch run measured (latencies, wall time, cores, the
// exactly-once check), how worker threads are run together, and how runs are
// reported: shared by the store-level and HTTP-level runs of farm_dispatch.cpp.
#include <chrono>
#include <cstdint>
#include <latch>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace vesper::farm_bench {

using Clock = std::chrono::steady_clock;

inline double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// CPU time of this process (user + system), seconds.
double cpu_seconds();

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
  int monitor_pages = 0;    // HTTP runs with simulated monitor pages (monitor_pages.h)
  int64_t monitor_requests = 0;
  int retries = 0;
  double wall = 0, cores = 0;
  std::vector<double> lease_ms, complete_ms, lease_in_ms, complete_in_ms;
  std::vector<std::string> problems;  // correctness failures; empty = every task exactly once

  // Adds the workers' latencies and problems; counts completions per task id in `tally`.
  void merge(std::vector<WorkerLog>& logs, std::map<int64_t, int>& tally);
};

// Nearest-rank percentile (p in [0, 1]) of unsorted values.
double percentile(std::vector<double> v, double p);

// Checks the workers' tally: `tasks` distinct tasks, each completed once.
void check_tally(const std::map<int64_t, int>& tally, int tasks, Run& run);

// Runs one thread per worker, `worker(w, log, ready)`; each calls ready()
// once, when it is set up, and the clock runs from when all are ready until
// the last one ends. Fills the run's wall time, cores and latencies and checks
// the workers' tally, which it returns (task id -> completions).
template <class F>
std::map<int64_t, int> run_workers(Run& run, F worker) {
  std::vector<WorkerLog> logs(static_cast<size_t>(run.workers));
  std::latch start(run.workers + 1);
  std::vector<std::thread> threads;
  for (int w = 0; w < run.workers; ++w)
    threads.emplace_back(
        [&, w] { worker(w, logs[static_cast<size_t>(w)], [&] { start.arrive_and_wait(); }); });
  const double cpu0 = cpu_seconds();
  start.arrive_and_wait();
  const auto t_start = Clock::now();
  for (auto& t : threads) t.join();
  run.wall = seconds_between(t_start, Clock::now());
  run.cores = (cpu_seconds() - cpu0) / run.wall;  // for HTTP runs, clients and server together

  std::map<int64_t, int> tally;
  run.merge(logs, tally);
  check_tally(tally, run.tasks, run);
  return tally;
}

void print_header();
void print_row(const Run& r, const char* label, const std::vector<double>& lease,
               const std::vector<double>& complete, bool rate);
// Prints each run's exactly-once check; returns 1 if one failed.
int print_checks(const std::vector<Run>& runs);

}  // namespace vesper::farm_bench
