#pragma once
// Open monitor pages, simulated: each is a thread with its own keep-alive
// httplib client that logs in once (POST /api/v1/login, the session cookie)
// and then, every `interval` seconds, makes the requests of one poll of the
// page (server/monitor/monitor.js) with the job page open — the heaviest
// view: GET /api/v1/jobs, GET /api/v1/workers and GET /api/v1/jobs/{job}
// with its first 500 tasks. Used by vesper_farm_bench to measure what open
// pages cost the workers.
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace vesper::farm_bench {

class MonitorPages {
 public:
  // Starts `pages` threads polling the server on 127.0.0.1:`port`.
  MonitorPages(int port, std::string submitter_token, int pages, double interval, int64_t job);
  ~MonitorPages();  // stops
  MonitorPages(const MonitorPages&) = delete;
  MonitorPages& operator=(const MonitorPages&) = delete;

  void stop();
  int64_t requests() const { return requests_; }  // answered 200
  int64_t failures() const { return failures_; }  // anything else (none expected)

 private:
  void page(int index);

  const int port_;
  const std::string token_;
  const int pages_;
  const double interval_;
  const int64_t job_;
  std::atomic<bool> stop_{false};
  std::atomic<int64_t> requests_{0}, failures_{0};
  std::vector<std::thread> threads_;
};

}  // namespace vesper::farm_bench
