#include "server/frame_merger.h"

#include <spdlog/spdlog.h>

#include <fstream>
#include <sstream>

#include "common/secret_token.h"
#include "common/sha256.h"
#include "jobs/job_store.h"
#include "server/blob_store.h"
#include "server/frame_noise.h"
#include "server/locked_store.h"
#include "server/merge.h"
#include "server/server_clock.h"

namespace fs = std::filesystem;

namespace vesper {

FrameMerger::FrameMerger(const FrameMergerConfig& config, LockedStore& store, BlobStore& blobs,
                         ServerClock& clock)
    : config_(config), store_(store), blobs_(blobs), clock_(clock) {
  merger_ = find_vesper_binary(config_.vesper_binary, merger_problem_);
  if (merger_.empty())
    spdlog::warn("merged frames of several tasks unavailable: {}", merger_problem_);
  // Merges killed with a previous server left only temp files: nothing was recorded.
  std::error_code ec;
  fs::remove_all(config_.data_dir / "merge-tmp", ec);
  fs::create_directories(config_.data_dir / "merge-tmp", ec);
}

FrameMerger::~FrameMerger() {
  request_stop();
  join();
}

std::string FrameMerger::frame_name(int64_t job, int frame) {
  return "frame " + std::to_string(frame) + " of job " + std::to_string(job);
}

std::optional<FrameMerger::Output> FrameMerger::output(int64_t job, int frame, bool retry) {
  const Key key{job, frame};
  for (;;) {
    const std::optional<FrameStatus> f =
        store_.with([&](JobStore& s) { return s.frame(job, frame); });
    if (!f) return std::nullopt;
    if (auto answer = without_merge(job, *f)) return answer;
    bool look_again = false;
    if (auto answer = claim(key, retry, look_again)) return answer;
    if (look_again) continue;
    return merge_claimed(key, f->results);
  }
}

// The answer when the frame needs no merge by this thread: it has an output,
// will not finish, is not finished, is one task, or merging is unavailable.
std::optional<FrameMerger::Output> FrameMerger::without_merge(int64_t job, const FrameStatus& f) {
  const std::string name = frame_name(job, f.frame);
  if (!f.output.empty()) return Output{State::Ready, f.output, {}};
  if (f.failed + f.canceled > 0)
    return Output{State::TasksFailed,
                  {},
                  name + " will not finish: " + std::to_string(f.failed) + " task(s) failed and " +
                      std::to_string(f.canceled) +
                      " canceled (POST .../retry-failed requeues failed tasks)"};
  if (!f.complete())
    return Output{State::Pending,
                  {},
                  name + " is not finished yet: " + std::to_string(f.done) + " of " +
                      std::to_string(f.tasks) + " tasks done"};
  if (f.tasks == 1)  // completed before outputs were recorded (an older store)
    return Output{State::Ready,
                  store_.with([&](JobStore& s) {
                    return s.record_frame_output(job, f.frame, f.results[0], clock_.now());
                  }),
                  {}};
  if (merger_.empty())
    return Output{State::Unavailable, {}, "merging is unavailable: " + merger_problem_};
  return std::nullopt;
}

// Claims the frame for a merge by this thread (nullopt), or answers without
// merging: another thread merges it (wait, then `look_again` at the store),
// or its last merge failed and may not be retried yet.
std::optional<FrameMerger::Output> FrameMerger::claim(const Key& key, bool retry,
                                                      bool& look_again) {
  std::unique_lock lock(mutex_);
  if (merging_.count(key)) {
    cv_.wait(lock, [&] { return !merging_.count(key) || stopping_.load(); });
    if (stopping_.load()) return Output{State::Stopping, {}, "the server is stopping"};
    if (auto it = failures_.find(key); it != failures_.end())
      return Output{State::MergeFailed, {}, it->second.error};
    look_again = true;
    return std::nullopt;
  }
  if (auto it = failures_.find(key); it != failures_.end()) {
    const double age =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second.when).count();
    if (!retry || age < config_.merge_retry_seconds)
      return Output{State::MergeFailed, {}, it->second.error};
  }
  merging_.insert(key);
  return std::nullopt;
}

FrameMerger::Output FrameMerger::merge_claimed(const Key& key,
                                               const std::vector<std::string>& results) {
  Output out;
  try {
    out = merge(key.first, key.second, results);
  } catch (const std::exception& e) {
    out = Output{State::MergeFailed, {}, std::string("merge failed: ") + e.what()};
  }
  {
    std::lock_guard lock(mutex_);
    merging_.erase(key);
    if (out.state == State::MergeFailed)
      failures_[key] = Failure{out.message, std::chrono::steady_clock::now()};
    else
      failures_.erase(key);
  }
  cv_.notify_all();
  return out;
}

// Runs `vesper merge` over the frame's results, stores the EXR as a blob and
// records it. Killed at any point before the record, it leaves nothing
// recorded (a stray temp file in merge-tmp/ is removed at the next start).
FrameMerger::Output FrameMerger::merge(int64_t job, int frame,
                                       const std::vector<std::string>& results) {
  std::vector<fs::path> inputs;
  for (const std::string& r : results) {
    auto file = blobs_.file(r);
    if (!file) return {State::MergeFailed, {}, "the result blob " + r + " of a task is missing"};
    inputs.push_back(*file);
  }
  const fs::path out = config_.data_dir / "merge-tmp" /
                       (std::to_string(job) + "-" + std::to_string(frame) + "-" +
                        std::to_string(++counter_) + "-" + random_hex(8) + ".exr");
  spdlog::info("{}: merging {} sample ranges", frame_name(job, frame), inputs.size());
  const auto started = std::chrono::steady_clock::now();
  const MergeRun run = run_vesper_merge(merger_, inputs, out, stopping_);
  if (run.aborted) return {State::Stopping, {}, run.error};
  if (!run.ok) {
    spdlog::error("{}: {}", frame_name(job, frame), run.error);
    return {State::MergeFailed, {}, run.error};
  }
  std::string bytes;
  {
    std::ifstream in(out, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    bytes = ss.str();
  }
  const FrameNoise noise = read_frame_noise(out);  // the merged frame's, from its header
  std::error_code ec;
  fs::remove(out, ec);
  const std::string hash = sha256_hex(bytes);
  blobs_.put(hash, bytes);
  const double put_before = BlobStore::now();
  // The frame is never seen ready without its noise: both in one transaction
  // (the API reads through a second connection, server/locked_store.h).
  const std::string recorded = store_.with(
      [&](JobStore& s) { return s.record_frame_output(job, frame, hash, clock_.now(), noise); });
  blobs_.claim({hash}, put_before);  // the frame references it now
  spdlog::info("{}: merged into {} in {:.2f} s", frame_name(job, frame), recorded,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  return {State::Ready, recorded, {}};
}

std::map<int, std::string> FrameMerger::failures(int64_t job) const {
  std::map<int, std::string> out;
  std::lock_guard lock(mutex_);
  for (const auto& [key, f] : failures_)
    if (key.first == job) out[key.second] = f.error;
  return out;
}

void FrameMerger::wake() {
  {
    std::lock_guard lock(mutex_);
    scan_ = true;
  }
  cv_.notify_all();
}

void FrameMerger::start() {
  thread_ = std::thread([this] { loop(); });
}

void FrameMerger::request_stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  cv_.notify_all();
}

void FrameMerger::join() {
  if (thread_.joinable()) thread_.join();
}

// Background: merges every finished frame that waits for a merge, after each
// wake() (and once at start). Failed merges are not retried here; a request
// retries them later.
void FrameMerger::loop() {
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      cv_.wait(lock, [&] { return scan_ || stopping_.load(); });
      if (stopping_.load()) return;
      scan_ = false;
    }
    // Outputs recorded without their noise: by an older server (at start), or
    // reused from one (after a lease).
    record_frame_noise(store_, blobs_);
    if (merger_.empty()) continue;
    std::vector<std::pair<int64_t, int>> todo;
    try {
      todo = store_.with([](JobStore& s) { return s.frames_awaiting_merge(); });
    } catch (const std::exception& e) {
      spdlog::error("merger: {}", e.what());
    }
    for (const auto& [job, frame] : todo) {
      if (stopping_.load()) return;
      try {
        output(job, frame, /*retry=*/false);
      } catch (const std::exception& e) {
        spdlog::error("merger: {}: {}", frame_name(job, frame), e.what());
      }
    }
  }
}

}  // namespace vesper
