#include "bench/farm/dispatch_run.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace vesper::farm_bench {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void Run::merge(std::vector<WorkerLog>& logs, std::map<int64_t, int>& tally) {
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

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  size_t k = size_t(std::ceil(p * double(v.size())));
  return v[std::min(v.size() - 1, k == 0 ? 0 : k - 1)];
}

void check_tally(const std::map<int64_t, int>& tally, int tasks, Run& run) {
  int twice = 0;
  for (const auto& [id, n] : tally)
    if (n != 1) ++twice;
  if (int(tally.size()) != tasks)
    run.problems.push_back("workers completed " + std::to_string(tally.size()) +
                           " distinct tasks, expected " + std::to_string(tasks));
  if (twice) run.problems.push_back(std::to_string(twice) + " tasks completed more than once");
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

int print_checks(const std::vector<Run>& runs) {
  int status = 0;
  for (const Run& r : runs) {
    std::string name =
        r.name == "store" ? "store" : (r.keep_alive ? "HTTP keep-alive" : "HTTP per request");
    if (r.monitor_pages > 0) name += " + monitor";
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

}  // namespace vesper::farm_bench
