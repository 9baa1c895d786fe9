#include "cli/farm_setup.h"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace vesper::cli {

ServerConfig server_config(const FarmSettings& s) {
  ServerConfig c;
  c.data_dir = expand_user(s.server.data_dir);
  c.host = s.server.host;
  c.port = s.server.port;
  c.lease_seconds = s.server.lease_seconds;
  c.blocklist_threshold = s.server.blocklist_threshold;
  c.max_blob_bytes = std::size_t(s.server.max_blob_mib) << 20;
  c.threads = s.server.threads;
  c.max_connections = s.server.max_connections;
  c.header_timeout = s.server.header_timeout;
  c.idle_timeout = s.server.idle_timeout;
  c.task_timeout = s.server.task_timeout;
  c.trusted_renderers = s.server.trusted_renderers;
  c.monitor_read_only = s.server.monitor_read_only;
  c.blob_grace_seconds = s.server.blob_grace_seconds;
  c.webhook_url = s.server.webhook_url;
  return c;
}

WorkerConfig worker_config(const FarmSettings& s) {
  WorkerConfig c;
  c.cache_dir = expand_user(s.worker.cache_dir);
  c.vesper_binary = self_executable();
  c.heartbeat_seconds = s.worker.heartbeat_seconds;
  c.idle_backoff_min = s.worker.idle_backoff_min;
  c.idle_backoff_max = s.worker.idle_backoff_max;
  c.render_threads = s.worker.render_threads;
  c.kill_grace_seconds = s.worker.kill_grace_seconds;
  c.cache_max_bytes = s.worker.cache_max_bytes;
  return c;
}

std::filesystem::path self_executable() {
  std::error_code ec;
  auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path("vesper") : p;
}

void exit_on_second_signal() {
  static std::atomic<int> signals{0};  // lock-free: safe in a signal handler
  if (signals.fetch_add(1) == 0) {
    static const char msg[] =
        "\nvesper: stopping after the current render (again to stop at once)\n";
    [[maybe_unused]] auto n = ::write(2, msg, sizeof msg - 1);
    return;
  }
  static const char msg[] = "\nvesper: stopped at once; running leases will expire\n";
  [[maybe_unused]] auto n = ::write(2, msg, sizeof msg - 1);
  ::_exit(130);
}

void on_stop_signals(void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace vesper::cli
