#pragma once
// Registered workers: id (random, handed out by POST /workers/register),
// name, registration and last-seen times (the server's clock, seconds).
// Registrations are persisted atomically to <data_dir>/workers.json so a
// restarted server still knows its workers; last-seen times are written with
// every registration and at shutdown (losing them in a crash is harmless).
// Thread safe.
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace vesper {

struct WorkerInfo {
  std::string id;
  std::string name;
  double registered = 0;
  double last_seen = 0;
};

class WorkerRegistry {
 public:
  explicit WorkerRegistry(std::filesystem::path file);
  // Registers a worker: `previous_id` (the id a restarted worker had) is
  // kept when known — its name and last-seen are updated, nothing is added —
  // else a new random id is made. Returns the id.
  std::string add(const std::string& name, double now, const std::string& previous_id = {});
  // Updates last-seen; false for an unknown id.
  bool touch(const std::string& id, double now);
  std::optional<WorkerInfo> find(const std::string& id) const;
  std::vector<WorkerInfo> list() const;
  void save() const;

 private:
  void save_locked() const;
  std::filesystem::path file_;
  mutable std::mutex mutex_;
  std::map<std::string, WorkerInfo> workers_;
};

}  // namespace vesper
