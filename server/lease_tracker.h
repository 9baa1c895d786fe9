#pragma once
// The leases this server process has handed out or seen, and the reaper.
// In memory only (lost on restart, refilled by the next lease): the job
// store is the authority on leases; this knows a live lease's progress (for
// task listings), its worker (for last-seen times and lease counts) and its
// expiry. The reaper thread requeues expired leases in the store and forgets
// them here. Thread safe.
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

namespace vesper {

class LockedStore;
class ServerClock;
class WorkerRegistry;

class LeaseTracker {
 public:
  LeaseTracker(LockedStore& store, ServerClock& clock, WorkerRegistry& workers,
               double lease_seconds);
  ~LeaseTracker();  // stops the reaper
  LeaseTracker(const LeaseTracker&) = delete;
  LeaseTracker& operator=(const LeaseTracker&) = delete;

  void granted(const std::string& lease_id, int64_t task_id, const std::string& worker_id,
               double expiry, int64_t job_id = 0);
  // A call on a lease at `now`: extends it, keeps `progress`, touches its
  // worker's last-seen; forgets the lease when it `ended`. Unknown leases
  // (granted before a restart) are ignored.
  void note(const std::string& lease_id, double now, bool ended,
            std::optional<double> progress = std::nullopt);

  std::map<int64_t, double> progress_by_task() const;
  std::map<std::string, int> leases_by_worker() const;
  // (job, task) of a live lease of each worker that holds one (one of them).
  std::map<std::string, std::pair<int64_t, int64_t>> task_by_worker() const;

  // Requeues expired leases every `interval` seconds on a background thread.
  void start_reaper(double interval);
  void stop_reaper();  // idempotent

 private:
  struct Live {
    int64_t task_id = 0;
    int64_t job_id = 0;
    std::string worker_id;
    double expiry = 0;
    double progress = 0;
  };
  void reap();

  LockedStore& store_;
  ServerClock& clock_;
  WorkerRegistry& workers_;
  const double lease_seconds_;
  mutable std::mutex mutex_;
  std::map<std::string, Live> live_;  // by lease id

  std::mutex stop_mutex_;
  std::condition_variable stop_cv_;
  bool stopping_ = false;
  std::thread reaper_;
};

}  // namespace vesper
