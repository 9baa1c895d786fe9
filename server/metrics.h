#pragma once
// The farm's metrics in Prometheus text exposition format (version 0.0.4).
#include <cstdint>
#include <map>
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

}  // namespace vesper
