#pragma once
// The id a worker keeps across restarts, so that a restarted worker is the
// same worker to the server (one entry in workers.json, its own blocklist
// history) rather than a new one each time. Kept in the cache dir, one slot
// file per running worker (cache_dir/worker-ids/<n>), each held with an
// exclusive flock for the worker's life: workers sharing a cache dir take
// different slots, a restarted worker (even after kill -9, which drops the
// lock) takes the first free one back with its id.
#include <filesystem>
#include <string>

namespace vesper::worker_detail {

class WorkerIdentity {
 public:
  // Takes the first free slot (of 64). With none free or the dir not
  // writable, the identity remembers nothing (a new id at every start).
  explicit WorkerIdentity(const std::filesystem::path& cache_dir);
  ~WorkerIdentity();
  WorkerIdentity(const WorkerIdentity&) = delete;
  WorkerIdentity& operator=(const WorkerIdentity&) = delete;

  // The id saved by the last worker of this slot ("" if none).
  const std::string& saved_id() const { return id_; }
  // Remembers the id the server gave (best effort).
  void save(const std::string& id);

 private:
  int fd_ = -1;
  std::string id_;
};

}  // namespace vesper::worker_detail
