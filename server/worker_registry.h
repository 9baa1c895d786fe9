#pragma once
// Registered workers: id (random, handed out by POST /workers/register),
// name, registration and last-seen times (the server's clock, seconds).
// Registrations are persisted atomically to <data_dir>/workers.json so a
// restarted server still knows its workers; last-seen times are written with
// every registration and at shutdown (losing them in a crash is harmless).
// A worker's state (online, offline, lost) follows from its last-seen time
// and whether it said goodbye (docs/farm.md, "Worker states"). Thread safe.
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
  bool said_goodbye = false;  // stopped cleanly; cleared by its next call
};

enum class WorkerState { Online, Offline, Lost };
const char* to_string(WorkerState s);  // "online", "offline", "lost"

// Not seen for this long (and no goodbye): offline rather than lost.
inline constexpr double kWorkerGoneSeconds = 86400;
// Online: seen within `lease_seconds` (a working worker calls at least once
// per lease time: idle polls and heartbeats) and no goodbye since. Offline:
// said goodbye, or not seen for kWorkerGoneSeconds. Lost: anything else — not
// seen within the lease time without a goodbye (killed, crashed, cut off).
WorkerState worker_state(const WorkerInfo& w, double now, double lease_seconds);

class WorkerRegistry {
 public:
  explicit WorkerRegistry(std::filesystem::path file);
  // Registers a worker: `previous_id` (the id a restarted worker had) is
  // kept when known — its name and last-seen are updated, nothing is added —
  // else a new random id is made. Returns the id.
  std::string add(const std::string& name, double now, const std::string& previous_id = {});
  // Updates last-seen (and clears a goodbye); false for an unknown id.
  bool touch(const std::string& id, double now);
  // The worker stopped cleanly (POST /workers/goodbye); false for an unknown id.
  bool goodbye(const std::string& id, double now);
  // Removes the workers whose state at `now` is offline or lost; returns their ids.
  std::vector<std::string> prune(double now, double lease_seconds);
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
