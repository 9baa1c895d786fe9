#pragma once
// The job API's messages (server/README.md, "Jobs"; docs/api/openapi.yaml):
// submit, job summaries and details, tasks, actions, frames, the worker list
// and blob uploads. Each converts to and from its JSON body with nlohmann's
// to_json/from_json; from_json throws nlohmann::json::exception on a missing
// key or wrong type (it reads what to_json writes). Optional fields are left
// out of the JSON when unset.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "protocol/worker_messages.h"

namespace vesper::protocol {

// POST /jobs. The defaults are the server's.
struct SubmitRequest {
  std::string name = "job";
  std::string scene;  // SHA-256 of the uploaded scene blob
  // "1-100", "1-100x5", "1,5,9" (combinations too), or a list of frames.
  std::variant<std::string, std::vector<int>> frames;
  int spp = 16;
  int samples_per_task = 0;  // 0: one task per frame
  int priority = 50;         // higher first
  int max_attempts = 3;
  std::vector<AssetRef> assets;  // left out of the JSON when empty
  // Adaptive sampling and a time budget (docs/farm.md, "Noise targets and
  // time limits"), as `vesper render` takes them; each left out when unset.
  std::optional<double> noise_target;   // relative error of each pixel's mean, > 0
  std::optional<int> min_spp, max_spp;  // with noise_target; max_spp replaces spp
  std::optional<double> time_limit;     // seconds of rendering per frame, > 0
  // Render overrides (docs/farm.md, "Render overrides"), as `vesper render`'s
  // --aov, --layer-variance, --seed, --scale, --half; each left out when unset.
  std::vector<std::string> aovs;  // AOV names instead of the scene's render.aovs
  bool layer_variance = false;
  std::optional<uint64_t> seed;  // instead of the scene's render.seed
  std::optional<double> scale;   // film size factor, in (0, 4]
  bool half = false;             // half-float colour channels
  // Seconds one render of one task may take before its worker kills it
  // (that attempt fails); left out: the server's default.
  std::optional<double> task_timeout;
};

// 201 answer to POST /jobs.
struct SubmitResponse {
  int64_t id = 0;
  int64_t task_count = 0;
};

// 200 answer to POST /jobs?dry_run=1 ({"dry_run": true, ...}).
struct DryRunResponse {
  std::string name;
  int64_t frame_count = 0;
  int64_t task_count = 0;
  bool dry_run = true;
};

struct JobCounts {
  int queued = 0, leased = 0, done = 0, failed = 0, canceled = 0, paused = 0;
};

// A job in GET /jobs and at the top of GET /jobs/{id}. Times are the
// server's clock (seconds since the Unix epoch), left out when unset.
struct JobSummary {
  int64_t id = 0;
  std::string name;
  int priority = 0;
  std::string state;  // "active", "paused", "done", "failed", "canceled"
  JobCounts counts;
  int total = 0;
  double submitted = 0;
  std::optional<double> started;   // first task leased or reused
  std::optional<double> finished;  // reached done, failed or canceled
  std::optional<double> eta;       // seconds left (an estimate), while active
  // Done, failed or canceled: nothing more will happen to the job.
  bool ended() const { return state == "done" || state == "failed" || state == "canceled"; }
};

struct JobList {
  std::vector<JobSummary> jobs;
  double now = 0;  // the server's clock, to compare the jobs' times with
};

// A task in GET /jobs/{id}.
struct TaskInfo {
  int64_t id = 0;
  int64_t job_id = 0;
  int frame = 0;
  int sample_begin = 0, sample_end = 0;
  std::string state;  // "queued", "leased", "done", "failed", "canceled", "paused"
  int attempts = 0;
  std::string worker;  // current or last lease holder
  std::string result;  // result blob, when done
  bool has_log = false;
  std::optional<double> progress;  // leased tasks whose heartbeat the server has seen
  int64_t reused_from = 0;         // 0: rendered (left out of the JSON)
  // The last attempt: leased, ended, and how long it took (once ended).
  std::optional<double> started, finished, duration;
};

// A frame in GET /jobs/{id}/frames.
enum class FrameState { Pending, Ready, Failed };
struct FrameInfo {
  int frame = 0;
  FrameState state = FrameState::Pending;
  int tasks = 0, done = 0;
  std::string blob;   // Ready: the output blob (left out when empty)
  std::string error;  // Failed: why (left out when empty)
  // Ready, from the output's metadata (left out when it does not say).
  std::optional<double> noise_reached;  // RMS over pixels of the relative error of the mean
  std::optional<double> spp_mean;       // samples per pixel, averaged over the pixels
  std::string stop_reason;              // spp, noise_target, max_spp, time_limit
  bool operator==(const FrameInfo&) const = default;
};

// GET /jobs/{id}: the summary's fields plus these.
struct JobDetail {
  JobSummary summary;
  std::vector<TaskInfo> tasks;
  std::vector<std::string> blocked_workers;  // worker ids on the job's blocklist
  std::vector<FrameInfo> frames;             // as GET /jobs/{id}/frames lists them
  std::optional<int64_t> tasks_next;         // more tasks: the next page's tasks_after
  double now = 0;                            // the server's clock
};

// POST /jobs/{id}/cancel|pause|resume|retry-failed
struct JobActionResponse {
  JobSummary job;
  std::optional<int> requeued;  // retry-failed only
};

struct FrameList {
  std::vector<FrameInfo> frames;
};

// The task a worker holds a live lease on.
struct WorkerTask {
  int64_t job = 0;
  int64_t task = 0;
  bool operator==(const WorkerTask&) const = default;
};

// A worker in GET /workers.
struct WorkerInfo {
  std::string worker_id;
  std::string name;
  double registered = 0;  // the server's clock, seconds
  double last_seen = 0;
  int leases = 0;  // live leases this server process knows of
  // "online" | "offline" | "lost" (docs/farm.md, "Worker states").
  std::string state;
  std::optional<WorkerTask> current_task;  // left out when idle
  std::vector<int64_t> blocklisted_for;    // job ids; left out when none
};

struct WorkerList {
  std::vector<WorkerInfo> workers;
  double now = 0;  // the server's clock, to compare last_seen with
};

// Answer to PUT /blobs/{sha256} (201 stored, 200 already there).
struct BlobStored {
  std::string sha256;
  int64_t size = 0;
};

VESPER_JSON_CONVERSIONS(SubmitRequest);
VESPER_JSON_CONVERSIONS(SubmitResponse);
VESPER_JSON_CONVERSIONS(DryRunResponse);
VESPER_JSON_CONVERSIONS(JobCounts);
VESPER_JSON_CONVERSIONS(JobSummary);
VESPER_JSON_CONVERSIONS(JobList);
VESPER_JSON_CONVERSIONS(TaskInfo);
VESPER_JSON_CONVERSIONS(JobDetail);
VESPER_JSON_CONVERSIONS(JobActionResponse);
VESPER_JSON_CONVERSIONS(FrameState);
VESPER_JSON_CONVERSIONS(FrameInfo);
VESPER_JSON_CONVERSIONS(FrameList);
VESPER_JSON_CONVERSIONS(WorkerTask);
VESPER_JSON_CONVERSIONS(WorkerInfo);
VESPER_JSON_CONVERSIONS(WorkerList);
VESPER_JSON_CONVERSIONS(BlobStored);

}  // namespace vesper::protocol
