#include "server/worker_registry.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "common/secret_token.h"

namespace fs = std::filesystem;

namespace vesper {

WorkerRegistry::WorkerRegistry(fs::path file) : file_(std::move(file)) {
  if (!fs::exists(file_)) return;
  std::ifstream in(file_);
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    const nlohmann::json doc = nlohmann::json::parse(ss.str());
    for (const auto& w : doc.at("workers")) {
      WorkerInfo info{w.at("worker_id").get<std::string>(), w.at("name").get<std::string>(),
                      w.at("registered").get<double>(), w.at("last_seen").get<double>(),
                      w.value("said_goodbye", false)};
      workers_[info.id] = info;
    }
  } catch (const std::exception& e) {
    throw std::runtime_error("worker registry " + file_.string() + " is corrupt: " + e.what());
  }
}

std::string WorkerRegistry::add(const std::string& name, double now,
                                const std::string& previous_id) {
  std::lock_guard lock(mutex_);
  auto known = workers_.find(previous_id);
  const std::string id = known != workers_.end() ? previous_id : random_hex(16);
  const double registered = known != workers_.end() ? known->second.registered : now;
  workers_[id] = WorkerInfo{id, name, registered, now, false};
  save_locked();
  return id;
}

bool WorkerRegistry::touch(const std::string& id, double now) {
  std::lock_guard lock(mutex_);
  auto it = workers_.find(id);
  if (it == workers_.end()) return false;
  it->second.last_seen = std::max(it->second.last_seen, now);
  it->second.said_goodbye = false;
  return true;
}

bool WorkerRegistry::goodbye(const std::string& id, double now) {
  std::lock_guard lock(mutex_);
  auto it = workers_.find(id);
  if (it == workers_.end()) return false;
  it->second.last_seen = std::max(it->second.last_seen, now);
  it->second.said_goodbye = true;
  save_locked();
  return true;
}

std::vector<std::string> WorkerRegistry::prune(double now, double lease_seconds) {
  std::lock_guard lock(mutex_);
  std::vector<std::string> gone;
  for (auto it = workers_.begin(); it != workers_.end();) {
    if (worker_state(it->second, now, lease_seconds) == WorkerState::Online) {
      ++it;
      continue;
    }
    gone.push_back(it->first);
    it = workers_.erase(it);
  }
  if (!gone.empty()) save_locked();
  return gone;
}

const char* to_string(WorkerState s) {
  switch (s) {
    case WorkerState::Online:
      return "online";
    case WorkerState::Offline:
      return "offline";
    case WorkerState::Lost:
      return "lost";
  }
  return "lost";
}

WorkerState worker_state(const WorkerInfo& w, double now, double lease_seconds) {
  if (w.said_goodbye) return WorkerState::Offline;
  const double unseen = now - w.last_seen;
  if (unseen <= lease_seconds) return WorkerState::Online;
  return unseen > kWorkerGoneSeconds ? WorkerState::Offline : WorkerState::Lost;
}

std::optional<WorkerInfo> WorkerRegistry::find(const std::string& id) const {
  std::lock_guard lock(mutex_);
  auto it = workers_.find(id);
  if (it == workers_.end()) return std::nullopt;
  return it->second;
}

std::vector<WorkerInfo> WorkerRegistry::list() const {
  std::lock_guard lock(mutex_);
  std::vector<WorkerInfo> out;
  for (const auto& [id, w] : workers_) out.push_back(w);
  std::sort(out.begin(), out.end(),
            [](const WorkerInfo& a, const WorkerInfo& b) { return a.registered < b.registered; });
  return out;
}

void WorkerRegistry::save() const {
  std::lock_guard lock(mutex_);
  save_locked();
}

void WorkerRegistry::save_locked() const {
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& [id, w] : workers_)
    arr.push_back({{"worker_id", w.id},
                   {"name", w.name},
                   {"registered", w.registered},
                   {"last_seen", w.last_seen},
                   {"said_goodbye", w.said_goodbye}});
  const std::string text = nlohmann::json{{"workers", arr}}.dump(2) + "\n";
  const fs::path tmp = file_.string() + ".tmp";
  {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) throw std::runtime_error("cannot write " + tmp.string());
    const bool ok =
        ::write(fd, text.data(), text.size()) == ssize_t(text.size()) && ::fsync(fd) == 0;
    ::close(fd);
    if (!ok) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, file_);
}

}  // namespace vesper
