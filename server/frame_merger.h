#pragma once
// Merged frame outputs. A frame of one task is that task's result; a frame
// split into sample ranges is merged by `vesper merge` in a child process
// (merge.h) into an EXR blob, recorded once in the store. A background
// thread merges every finished frame that waits for a merge (woken after
// completions, and once at start for merges a restart interrupted); a
// request for a frame merges it too. A frame is merged by one thread at a
// time (others wait for it). A failed merge is remembered in memory and
// retried only on request, after merge_retry_seconds. Thread safe.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace vesper {

class BlobStore;
class LockedStore;
class ServerClock;
struct FrameStatus;

struct FrameMergerConfig {
  std::filesystem::path data_dir;       // merges in flight go to data_dir/merge-tmp
  std::filesystem::path vesper_binary;  // empty: `vesper` next to this executable
  double merge_retry_seconds = 60;
};

class FrameMerger {
 public:
  FrameMerger(const FrameMergerConfig& config, LockedStore& store, BlobStore& blobs,
              ServerClock& clock);
  ~FrameMerger();  // stops
  FrameMerger(const FrameMerger&) = delete;
  FrameMerger& operator=(const FrameMerger&) = delete;

  enum class State { Ready, Pending, TasksFailed, Unavailable, MergeFailed, Stopping };
  struct Output {
    State state = State::Pending;
    std::string blob;     // Ready
    std::string message;  // otherwise
  };

  // The output of a frame, merging it first if it needs a merge and none ran
  // yet (or, with `retry`, the last one failed more than merge_retry_seconds
  // ago). Waits for a merge of the same frame in flight. nullopt: the job has
  // no such frame.
  std::optional<Output> output(int64_t job, int frame, bool retry);
  // Frame -> error of the job's failed merges.
  std::map<int, std::string> failures(int64_t job) const;

  // Tasks completed: a frame of several tasks may be ready to merge.
  void wake();
  void start();  // the background merger
  // Kills merges in flight and makes waiting requests answer Stopping; then
  // join() waits for the background thread.
  void request_stop();
  void join();

  static std::string frame_name(int64_t job, int frame);

 private:
  using Key = std::pair<int64_t, int>;
  struct Failure {
    std::string error;
    std::chrono::steady_clock::time_point when;
  };
  std::optional<Output> without_merge(int64_t job, const FrameStatus& f);
  std::optional<Output> claim(const Key& key, bool retry, bool& look_again);
  Output merge_claimed(const Key& key, const std::vector<std::string>& results);
  Output merge(int64_t job, int frame, const std::vector<std::string>& results);
  void loop();

  const FrameMergerConfig config_;
  LockedStore& store_;
  BlobStore& blobs_;
  ServerClock& clock_;
  std::filesystem::path merger_;  // the vesper binary; empty: merging unavailable
  std::string merger_problem_;

  std::atomic<bool> stopping_{false};
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  bool scan_ = true;  // the background merger should look for frames to merge
  std::set<Key> merging_;
  std::map<Key, Failure> failures_;
  std::atomic<uint64_t> counter_{0};
  std::thread thread_;
};

}  // namespace vesper
