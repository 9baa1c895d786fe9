#include "worker/lease_retry.h"

#include <spdlog/spdlog.h>

#include "worker/server_api.h"

namespace vesper::worker_detail {

bool worth_retrying(const HttpResponse& r) { return r.status == 0 || r.status >= 500; }

LeaseRetry::LeaseRetry(double lease_seconds, Backoff backoff, const std::atomic<bool>& stop)
    : lease_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(lease_seconds))),
      backoff_(std::move(backoff)),
      stop_(stop) {
  confirmed();
}

void LeaseRetry::confirmed() { deadline_ = Clock::now() + lease_; }

HttpResponse LeaseRetry::call(const std::function<HttpResponse()>& call, const std::string& what,
                              int64_t task_id) {
  gave_up_ = false;
  const auto started = Clock::now();
  for (int tries = 1;; ++tries) {
    HttpResponse r = call();
    if (!worth_retrying(r)) {
      if (tries > 1)
        spdlog::info("task {}: {} succeeded after {} tries ({:.1f} s)", task_id, what, tries,
                     std::chrono::duration<double>(Clock::now() - started).count());
      return r;
    }
    // Unreachable: the server may be restarting, and renews leases when it starts.
    if (r.status == 0) deadline_ = std::max(deadline_, Clock::now() + lease_);
    if (Clock::now() >= deadline_ || stop_.load()) {
      spdlog::warn("task {}: giving up {} after {} tries ({}): {}", task_id, what, tries,
                   stop_.load() ? "stop requested" : "the lease has run out", describe(r));
      gave_up_ = true;
      return r;
    }
    spdlog::warn("task {}: {} failed ({}); retrying", task_id, what, describe(r));
    if (!backoff_.sleep(stop_)) {
      gave_up_ = true;
      return r;
    }
  }
}

}  // namespace vesper::worker_detail
