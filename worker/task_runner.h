#pragma once
// Runs a task's child render to its end while heartbeating: the worker's
// "run" state, without HTTP (the heartbeat is a callback).
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vesper::worker_detail {

struct RenderWatch {
  double heartbeat_seconds = 5;   // between heartbeats while the child runs
  double kill_grace_seconds = 2;  // SIGTERM → SIGKILL delay when the render is dropped
  // How long the same scene and sample count took last time, for a progress
  // estimate until the render reports its own.
  std::optional<double> expected_seconds;
  size_t log_tail_bytes = 64 * 1024;  // stderr kept for the failure log
  // Seconds the render may take (the task timeout); a longer one is killed
  // (SIGTERM to its process group, SIGKILL after the grace) and TimedOut.
  std::optional<double> timeout_seconds;
};

struct RenderRun {
  enum class End {
    NotStarted,  // the child could not be spawned (`status` says why)
    Dropped,     // the heartbeat said stop: the child was killed
    TimedOut,    // it ran past watch.timeout_seconds: the child was killed
    Exited,      // the child ended by itself; `succeeded` when its exit code is 0
  };
  End end = End::NotStarted;
  bool succeeded = false;
  std::string status;  // "exit code 2", "killed by signal 11 (Segmentation fault)", spawn error
  std::string stderr_tail;
  double seconds = 0;
  long pid = 0;  // the child's (its process group's) id, for logs
};

// The progress to report after `elapsed` seconds: the render's own last
// progress line, else elapsed / expected (capped at 0.99), else 0.5.
double estimate_progress(double elapsed, std::optional<double> expected_seconds,
                         const std::string& stderr_tail);

// Starts `argv` (process/child_process.h) and waits for it, calling
// `heartbeat(progress)` every watch.heartbeat_seconds; when that returns
// false the child is killed and the run is Dropped; when it runs past
// watch.timeout_seconds it is killed and the run TimedOut.
RenderRun run_render(const std::vector<std::string>& argv, const RenderWatch& watch,
                     const std::function<bool(double progress)>& heartbeat);

}  // namespace vesper::worker_detail
