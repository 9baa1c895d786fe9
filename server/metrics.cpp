#include "server/metrics.h"

namespace vesper {

std::string prometheus_text(const MetricsSnapshot& m) {
  std::string out;
  auto line = [&](const std::string& s) { out += s + "\n"; };
  line("# HELP vesper_jobs_total Jobs in the store.");
  line("# TYPE vesper_jobs_total gauge");
  line("vesper_jobs_total " + std::to_string(m.jobs));
  line("# HELP vesper_tasks Tasks in the store by state.");
  line("# TYPE vesper_tasks gauge");
  for (const auto& [state, n] : m.tasks_by_state)
    line("vesper_tasks{state=\"" + state + "\"} " + std::to_string(n));
  line("# HELP vesper_workers Registered workers.");
  line("# TYPE vesper_workers gauge");
  line("vesper_workers " + std::to_string(m.workers));
  line("# HELP vesper_leases_granted_total Task leases granted since the server started.");
  line("# TYPE vesper_leases_granted_total counter");
  line("vesper_leases_granted_total " + std::to_string(m.leases_granted));
  line(
      "# HELP vesper_tasks_reused_total Tasks completed with the result of an identical task "
      "(not rendered again) since the server started.");
  line("# TYPE vesper_tasks_reused_total counter");
  line("vesper_tasks_reused_total " + std::to_string(m.tasks_reused));
  line(
      "# HELP vesper_http_requests_total HTTP requests answered since the server started, by "
      "status code.");
  line("# TYPE vesper_http_requests_total counter");
  for (const auto& [code, n] : m.http_requests_by_code)
    line("vesper_http_requests_total{code=\"" + std::to_string(code) + "\"} " + std::to_string(n));
  return out;
}

void ServerCounters::response(int status) {
  std::lock_guard lock(mutex_);
  ++http_codes_[status];
}

void ServerCounters::fill(MetricsSnapshot& m) const {
  m.leases_granted = leases_granted_.load();
  m.tasks_reused = tasks_reused_.load();
  std::lock_guard lock(mutex_);
  m.http_requests_by_code = http_codes_;
}

}  // namespace vesper
