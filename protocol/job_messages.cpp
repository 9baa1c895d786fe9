#include "protocol/job_messages.h"

#include <nlohmann/json.hpp>

#include "protocol/fields.h"

namespace vesper::protocol {

using nlohmann::json;
namespace f = field;

void to_json(json& j, const SubmitRequest& m) {
  j = {{f::kName, m.name},         {f::kScene, m.scene},
       {f::kSpp, m.spp},           {f::kSamplesPerTask, m.samples_per_task},
       {f::kPriority, m.priority}, {f::kMaxAttempts, m.max_attempts}};
  std::visit([&](const auto& frames) { j[f::kFrames] = frames; }, m.frames);
  if (!m.assets.empty()) j[f::kAssets] = m.assets;
}
void from_json(const json& j, SubmitRequest& m) {
  const SubmitRequest defaults;
  m.name = j.value(f::kName, defaults.name);
  j.at(f::kScene).get_to(m.scene);
  const json& frames = j.at(f::kFrames);
  if (frames.is_string())
    m.frames = frames.get<std::string>();
  else
    m.frames = frames.get<std::vector<int>>();
  m.spp = j.value(f::kSpp, defaults.spp);
  m.samples_per_task = j.value(f::kSamplesPerTask, defaults.samples_per_task);
  m.priority = j.value(f::kPriority, defaults.priority);
  m.max_attempts = j.value(f::kMaxAttempts, defaults.max_attempts);
  m.assets = j.value(f::kAssets, std::vector<AssetRef>{});
}

void to_json(json& j, const SubmitResponse& m) {
  j = {{f::kId, m.id}, {f::kTaskCount, m.task_count}};
}
void from_json(const json& j, SubmitResponse& m) {
  j.at(f::kId).get_to(m.id);
  j.at(f::kTaskCount).get_to(m.task_count);
}

void to_json(json& j, const DryRunResponse& m) {
  j = {{f::kDryRun, true},
       {f::kName, m.name},
       {f::kFrameCount, m.frame_count},
       {f::kTaskCount, m.task_count}};
}
void from_json(const json& j, DryRunResponse& m) {
  j.at(f::kName).get_to(m.name);
  j.at(f::kFrameCount).get_to(m.frame_count);
  j.at(f::kTaskCount).get_to(m.task_count);
}

void to_json(json& j, const JobCounts& m) {
  j = {{f::kQueued, m.queued}, {f::kLeased, m.leased},     {f::kDone, m.done},
       {f::kFailed, m.failed}, {f::kCanceled, m.canceled}, {f::kPaused, m.paused}};
}
void from_json(const json& j, JobCounts& m) {
  j.at(f::kQueued).get_to(m.queued);
  j.at(f::kLeased).get_to(m.leased);
  j.at(f::kDone).get_to(m.done);
  j.at(f::kFailed).get_to(m.failed);
  j.at(f::kCanceled).get_to(m.canceled);
  j.at(f::kPaused).get_to(m.paused);
}

void to_json(json& j, const JobSummary& m) {
  j = {{f::kId, m.id},
       {f::kName, m.name},
       {f::kPriority, m.priority},
       {f::kState, m.state},
       {f::kCounts, m.counts},
       {f::kTotal, m.total},
       {f::kFinished, m.finished}};
}
void from_json(const json& j, JobSummary& m) {
  j.at(f::kId).get_to(m.id);
  j.at(f::kName).get_to(m.name);
  j.at(f::kPriority).get_to(m.priority);
  j.at(f::kState).get_to(m.state);
  j.at(f::kCounts).get_to(m.counts);
  j.at(f::kTotal).get_to(m.total);
  j.at(f::kFinished).get_to(m.finished);
}

void to_json(json& j, const JobList& m) { j = {{f::kJobs, m.jobs}}; }
void from_json(const json& j, JobList& m) { j.at(f::kJobs).get_to(m.jobs); }

void to_json(json& j, const TaskInfo& m) {
  j = {{f::kId, m.id},
       {f::kJobId, m.job_id},
       {f::kFrame, m.frame},
       {f::kSampleBegin, m.sample_begin},
       {f::kSampleEnd, m.sample_end},
       {f::kState, m.state},
       {f::kAttempts, m.attempts},
       {f::kWorker, m.worker},
       {f::kResult, m.result},
       {f::kHasLog, m.has_log}};
  if (m.progress) j[f::kProgress] = *m.progress;
  if (m.reused_from) j[f::kReusedFrom] = m.reused_from;
}
void from_json(const json& j, TaskInfo& m) {
  j.at(f::kId).get_to(m.id);
  j.at(f::kJobId).get_to(m.job_id);
  j.at(f::kFrame).get_to(m.frame);
  j.at(f::kSampleBegin).get_to(m.sample_begin);
  j.at(f::kSampleEnd).get_to(m.sample_end);
  j.at(f::kState).get_to(m.state);
  j.at(f::kAttempts).get_to(m.attempts);
  j.at(f::kWorker).get_to(m.worker);
  j.at(f::kResult).get_to(m.result);
  j.at(f::kHasLog).get_to(m.has_log);
  m.progress.reset();
  if (j.contains(f::kProgress)) m.progress = j.at(f::kProgress).get<double>();
  m.reused_from = j.value(f::kReusedFrom, int64_t(0));
}

void to_json(json& j, const JobDetail& m) {
  j = m.summary;
  j[f::kTasks] = m.tasks;
  j[f::kBlockedWorkers] = m.blocked_workers;
}
void from_json(const json& j, JobDetail& m) {
  j.get_to(m.summary);
  j.at(f::kTasks).get_to(m.tasks);
  j.at(f::kBlockedWorkers).get_to(m.blocked_workers);
}

void to_json(json& j, const JobActionResponse& m) {
  j = {{f::kJob, m.job}};
  if (m.requeued) j[f::kRequeued] = *m.requeued;
}
void from_json(const json& j, JobActionResponse& m) {
  j.at(f::kJob).get_to(m.job);
  m.requeued.reset();
  if (j.contains(f::kRequeued)) m.requeued = j.at(f::kRequeued).get<int>();
}

namespace {
constexpr const char* kFrameStates[] = {"pending", "ready", "failed"};  // by FrameState
}  // namespace

void to_json(json& j, const FrameState& m) { j = kFrameStates[int(m)]; }
void from_json(const json& j, FrameState& m) {
  const std::string s = j.get<std::string>();
  for (int i = 0; i < 3; ++i)
    if (s == kFrameStates[i]) {
      m = FrameState(i);
      return;
    }
  throw json::other_error::create(501, "unknown frame state '" + s + "'", &j);
}

void to_json(json& j, const FrameInfo& m) {
  j = {{f::kFrame, m.frame}, {f::kState, m.state}, {f::kTasks, m.tasks}, {f::kDone, m.done}};
  if (!m.blob.empty()) j[f::kBlob] = m.blob;
  if (!m.error.empty()) j[f::kError] = m.error;
}
void from_json(const json& j, FrameInfo& m) {
  j.at(f::kFrame).get_to(m.frame);
  j.at(f::kState).get_to(m.state);
  j.at(f::kTasks).get_to(m.tasks);
  j.at(f::kDone).get_to(m.done);
  m.blob = j.value(f::kBlob, "");
  m.error = j.value(f::kError, "");
}

void to_json(json& j, const FrameList& m) { j = {{f::kFrames, m.frames}}; }
void from_json(const json& j, FrameList& m) { j.at(f::kFrames).get_to(m.frames); }

void to_json(json& j, const WorkerInfo& m) {
  j = {{f::kWorkerId, m.worker_id},
       {f::kName, m.name},
       {f::kRegistered, m.registered},
       {f::kLastSeen, m.last_seen},
       {f::kLeases, m.leases}};
}
void from_json(const json& j, WorkerInfo& m) {
  j.at(f::kWorkerId).get_to(m.worker_id);
  j.at(f::kName).get_to(m.name);
  j.at(f::kRegistered).get_to(m.registered);
  j.at(f::kLastSeen).get_to(m.last_seen);
  j.at(f::kLeases).get_to(m.leases);
}

void to_json(json& j, const WorkerList& m) { j = {{f::kWorkers, m.workers}, {f::kNow, m.now}}; }
void from_json(const json& j, WorkerList& m) {
  j.at(f::kWorkers).get_to(m.workers);
  j.at(f::kNow).get_to(m.now);
}

void to_json(json& j, const BlobStored& m) { j = {{f::kSha256, m.sha256}, {f::kSize, m.size}}; }
void from_json(const json& j, BlobStored& m) {
  j.at(f::kSha256).get_to(m.sha256);
  j.at(f::kSize).get_to(m.size);
}

}  // namespace vesper::protocol
