#include "server/lease_tracker.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "server/locked_store.h"
#include "server/server_clock.h"
#include "server/worker_registry.h"

namespace vesper {

LeaseTracker::LeaseTracker(LockedStore& store, ServerClock& clock, WorkerRegistry& workers,
                           double lease_seconds)
    : store_(store), clock_(clock), workers_(workers), lease_seconds_(lease_seconds) {}

LeaseTracker::~LeaseTracker() { stop_reaper(); }

void LeaseTracker::granted(const std::string& lease_id, int64_t task_id,
                           const std::string& worker_id, double expiry, int64_t job_id) {
  std::lock_guard lock(mutex_);
  live_[lease_id] = Live{task_id, job_id, worker_id, expiry, 0};
}

void LeaseTracker::note(const std::string& lease_id, double now, bool ended,
                        std::optional<double> progress) {
  std::string worker;
  {
    std::lock_guard lock(mutex_);
    auto it = live_.find(lease_id);
    if (it == live_.end()) return;
    worker = it->second.worker_id;
    if (progress) it->second.progress = *progress;
    it->second.expiry = now + lease_seconds_;
    if (ended) live_.erase(it);
  }
  workers_.touch(worker, now);
}

std::map<int64_t, double> LeaseTracker::progress_by_task() const {
  std::map<int64_t, double> out;
  std::lock_guard lock(mutex_);
  for (const auto& [id, l] : live_) out[l.task_id] = l.progress;
  return out;
}

std::map<std::string, int> LeaseTracker::leases_by_worker() const {
  std::map<std::string, int> out;
  std::lock_guard lock(mutex_);
  for (const auto& [id, l] : live_) ++out[l.worker_id];
  return out;
}

std::map<std::string, std::pair<int64_t, int64_t>> LeaseTracker::task_by_worker() const {
  std::map<std::string, std::pair<int64_t, int64_t>> out;
  std::lock_guard lock(mutex_);
  for (const auto& [id, l] : live_) out[l.worker_id] = {l.job_id, l.task_id};
  return out;
}

void LeaseTracker::start_reaper(double interval) {
  reaper_ = std::thread([this, interval] {
    std::unique_lock lk(stop_mutex_);
    while (!stop_cv_.wait_for(lk, std::chrono::duration<double>(interval),
                              [&] { return stopping_; })) {
      lk.unlock();
      reap();
      lk.lock();
    }
  });
}

void LeaseTracker::stop_reaper() {
  {
    std::lock_guard lock(stop_mutex_);
    stopping_ = true;
  }
  stop_cv_.notify_all();
  if (reaper_.joinable()) reaper_.join();
}

void LeaseTracker::reap() {
  try {
    const double t = clock_.now();
    const int n = store_.with([&](JobStore& s) { return s.expire_leases(t); });
    if (n) spdlog::warn("{} expired lease(s) requeued", n);
    std::lock_guard lock(mutex_);
    for (auto it = live_.begin(); it != live_.end();)
      it = it->second.expiry < t ? live_.erase(it) : std::next(it);
  } catch (const std::exception& e) {
    spdlog::error("lease reaper: {}", e.what());
  }
}

}  // namespace vesper
