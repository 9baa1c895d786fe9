#include "worker/task_runner.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include "process/child_process.h"
#include "worker/render_progress.h"

namespace vesper::worker_detail {

double estimate_progress(double elapsed, std::optional<double> expected_seconds,
                         const std::string& stderr_tail) {
  if (const auto reported = last_render_progress(stderr_tail)) return *reported;
  if (expected_seconds && *expected_seconds > 0) return std::min(0.99, elapsed / *expected_seconds);
  return 0.5;
}

RenderRun run_render(const std::vector<std::string>& argv, const RenderWatch& watch,
                     const std::function<bool(double progress)>& heartbeat) {
  using Clock = std::chrono::steady_clock;
  RenderRun run;
  std::unique_ptr<ChildProcess> child;
  try {
    child = std::make_unique<ChildProcess>(argv, watch.log_tail_bytes);
  } catch (const std::exception& e) {
    run.status = e.what();
    return run;
  }
  const auto started = Clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(Clock::now() - started).count();
  };
  run.end = RenderRun::End::Exited;
  run.pid = long(child->pid());
  const double timeout = watch.timeout_seconds.value_or(std::numeric_limits<double>::infinity());
  auto next_beat = watch.heartbeat_seconds;
  for (;;) {
    // Wake for the next heartbeat or the timeout, whichever comes first.
    if (child->wait_for(std::max(0.0, std::min(next_beat, timeout) - elapsed()))) break;
    if (elapsed() >= timeout) {
      child->kill(watch.kill_grace_seconds);
      run.end = RenderRun::End::TimedOut;
      break;
    }
    if (elapsed() < next_beat) continue;
    next_beat = elapsed() + watch.heartbeat_seconds;
    if (!heartbeat(estimate_progress(elapsed(), watch.expected_seconds, child->stderr_tail()))) {
      child->kill(watch.kill_grace_seconds);
      run.end = RenderRun::End::Dropped;
      break;
    }
  }
  run.seconds = elapsed();
  run.succeeded = run.end == RenderRun::End::Exited && child->exit_code() == 0;
  run.status = child->describe_status();
  run.stderr_tail = child->stderr_tail();
  return run;
}

}  // namespace vesper::worker_detail
