#pragma once
// The farm worker: registers with a server, leases tasks, downloads the scene
// blob into a sha256-verified cache, renders the task in a child `vesper
// render` process (a crashing render fails the task, not the worker),
// heartbeats with progress, uploads the EXR result and completes the task.
// See worker/README.md for the protocol details.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace vesper {

struct WorkerConfig {
  std::string server_url;               // http://host:port (the API is under /api/v1)
  std::string token;                    // the server's worker token
  std::string name;                     // shown in GET /workers (default: hostname)
  std::filesystem::path cache_dir;      // blob cache (<sha>.json) and render temp files
  std::filesystem::path vesper_binary;  // the `vesper` executable used to render in a child process
  double heartbeat_seconds = 5;
  // Jittered exponential back-off while there is no work (or the server is
  // unreachable), in seconds.
  double idle_backoff_min = 0.2, idle_backoff_max = 5;
  int max_tasks = -1;           // stop after N tasks (tests); -1 = no limit
  bool exit_when_idle = false;  // return 0 at the first "no work" answer
  int render_threads = 0;       // --threads for the child render; 0 = renderer default (all cores)
  double kill_grace_seconds = 2;  // SIGTERM → SIGKILL delay when a render is dropped
  // Cap of the blob cache (bytes): least recently used blobs are evicted
  // beyond it, never the current task's (worker/cache_eviction.h).
  std::int64_t cache_max_bytes = std::int64_t(10) << 30;
  // Send the renderer's sha256 with each lease, so the server may complete a
  // task with the result of an identical one this same renderer build already
  // rendered. Off for a renderer whose output the file's hash does not pin
  // (a wrapper script that runs something else).
  bool reuse_results = true;
};

class Worker {
 public:
  explicit Worker(WorkerConfig config);
  ~Worker();
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // The lease loop. Returns the exit code: 0 after request_stop(), max_tasks
  // or (exit_when_idle) no work; 1 on a fatal error (bad token, bad config).
  int run();
  // Async-signal-safe and thread-safe (sets an atomic flag). A render in
  // progress is finished and its task completed (or failed) first; then run()
  // returns. While idle, run() returns within ~50 ms.
  void request_stop() noexcept;

  // The id the server gave at registration (empty before run() registered).
  std::string worker_id() const;
  // Tasks finished by this worker so far: completed / failed / dropped (stop or stale lease).
  int tasks_completed() const { return completed_.load(); }
  int tasks_failed() const { return failed_.load(); }
  int tasks_dropped() const { return dropped_.load(); }

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
  std::atomic<bool> stop_{false};
  std::atomic<int> completed_{0}, failed_{0}, dropped_{0};
};

}  // namespace vesper
