#pragma once
// The server's `now` for the job store (lease expiry): the configured clock,
// or the wall clock (seconds since the Unix epoch; lease expiries are
// persisted and must keep their meaning across a restart), clamped so it
// never runs backwards within the process. Thread safe.
#include <functional>
#include <mutex>

namespace vesper {

class ServerClock {
 public:
  explicit ServerClock(std::function<double()> source) : source_(std::move(source)) {}
  double now();

 private:
  std::function<double()> source_;  // empty: the wall clock
  std::mutex mutex_;
  double last_ = 0;
};

}  // namespace vesper
