#include "worker/backoff.h"

#include <algorithm>
#include <chrono>
#include <thread>

namespace vesper::worker_detail {
namespace {

using Clock = std::chrono::steady_clock;

// Sleeps for `seconds` in 50 ms slices; returns false early if stop was requested.
bool sleep_unless_stopped(const std::atomic<bool>& stop, double seconds) {
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(seconds));
  while (Clock::now() < deadline) {
    if (stop.load()) return false;
    const Clock::duration left = deadline - Clock::now();
    std::this_thread::sleep_for(std::min<Clock::duration>(std::chrono::milliseconds(50), left));
  }
  return !stop.load();
}

}  // namespace

Backoff::Backoff(double min_seconds, double max_seconds)
    : min_(std::max(min_seconds, 0.001)), max_(std::max(max_seconds, min_)) {}

bool Backoff::sleep(const std::atomic<bool>& stop) {
  current_ = current_ <= 0 ? min_ : std::min(current_ * 2, max_);
  std::uniform_real_distribution<double> jitter(0.5, 1.0);
  return sleep_unless_stopped(stop, current_ * jitter(rng_));
}

}  // namespace vesper::worker_detail
