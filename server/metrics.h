#pragma once
// The farm's metrics in Prometheus text exposition format (version 0.0.4).
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace vesper {

struct MetricsSnapshot {
  int64_t jobs = 0;
  std::map<std::string, int64_t> tasks_by_state;  // every state, zeros included
  int64_t workers = 0;
  uint64_t leases_granted = 0;                    // since the server started
  uint64_t tasks_reused = 0;                      // identical tasks not rendered again, since start
  std::map<int, uint64_t> http_requests_by_code;  // since the server started
};

std::string prometheus_text(const MetricsSnapshot& m);

// The counters since the server started. Thread safe.
class ServerCounters {
 public:
  void lease_granted() { ++leases_granted_; }
  void tasks_reused(int n) { tasks_reused_ += uint64_t(n); }
  // Counted before the response is written, so a client that got an answer
  // sees it in the next /metrics.
  void response(int status);
  // Fills the counter fields of `m`.
  void fill(MetricsSnapshot& m) const;

 private:
  std::atomic<uint64_t> leases_granted_{0};
  std::atomic<uint64_t> tasks_reused_{0};
  mutable std::mutex mutex_;
  std::map<int, uint64_t> http_codes_;
};

}  // namespace vesper
