#pragma once
// Jittered exponential back-off for a worker with no work or no server: each
// sleep is uniform in [b/2, b], b doubling from `min_seconds` up to
// `max_seconds`, so that many idle workers do not poll in step.
#include <atomic>
#include <random>

namespace vesper::worker_detail {

class Backoff {
 public:
  Backoff(double min_seconds, double max_seconds);
  // Sleeps the next back-off in 50 ms slices; false as soon as `stop` is set.
  bool sleep(const std::atomic<bool>& stop);
  // The next sleep starts again from the minimum (after a success).
  void reset() { current_ = 0; }

 private:
  double min_, max_, current_ = 0;
  std::mt19937_64 rng_{std::random_device{}()};
};

}  // namespace vesper::worker_detail
