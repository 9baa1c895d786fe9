#pragma once
// How long a worker keeps retrying the calls of a task it holds (download of
// its inputs, upload of its result, completion): for as long as the lease
// could still be alive, with jittered back-off. A finished render is worth
// minutes of patience; three quick tries lost it to a server restart of
// 1.4 s. The rules:
//  - a transport error (server unreachable) is retried without a deadline:
//    a restarting server gives every lease a full lease_seconds when it
//    starts (server/README.md), so the lease cannot run out while the
//    server is away;
//  - a 5xx is retried until lease_seconds after the server last confirmed
//    the lease (its grant, a heartbeat): then the server's reaper has
//    requeued the task anyway;
//  - anything else is the answer; a stop request ends the retries.
// Giving up is an infrastructure failure, not the task's: the worker drops
// the task without POST /fail, so no attempt is charged and the worker is
// not blocklisted for it (the lease expires, the task runs again).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "worker/backoff.h"
#include "worker/http_client.h"

namespace vesper::worker_detail {

class LeaseRetry {
 public:
  // The lease was granted now and lives `lease_seconds` unless renewed.
  LeaseRetry(double lease_seconds, Backoff backoff, const std::atomic<bool>& stop);

  // The server confirmed the lease now (a heartbeat it accepted).
  void confirmed();

  // Calls `call` until its answer is not worth retrying (see above) and
  // returns the last answer; gave_up() then says whether retrying stopped
  // while the answer still was a transport error or a 5xx. `what` and
  // `task_id` label the log lines.
  HttpResponse call(const std::function<HttpResponse()>& call, const std::string& what,
                    int64_t task_id);
  bool gave_up() const { return gave_up_; }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::duration lease_;
  Clock::time_point deadline_;
  Backoff backoff_;
  const std::atomic<bool>& stop_;
  bool gave_up_ = false;
};

// A transport error or a 5xx: the server is away or in trouble, not refusing.
bool worth_retrying(const HttpResponse& r);

}  // namespace vesper::worker_detail
