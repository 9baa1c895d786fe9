#pragma once
// The worker protocol's messages (server/README.md, "Worker protocol";
// docs/api/openapi.yaml): register, lease, heartbeat, complete, fail. Each
// converts to and from its JSON body with nlohmann's to_json/from_json;
// from_json throws nlohmann::json::exception on a missing key or wrong type
// (the server validates requests itself, with JSON paths in its errors).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "protocol/json_conversions.h"

namespace vesper::protocol {

// POST /workers/register
struct RegisterRequest {
  std::string name;  // at most 128 characters, no control characters
  // The id this worker had before (a restart): kept when the server knows it,
  // so a restarted worker is the same worker (its blocklist entries, one
  // line in workers.json) instead of a new one. Empty: a new id.
  std::string worker_id;
};
struct RegisterResponse {
  std::string worker_id;
};

// A file the scene references, sent as a blob: `name` is the relative path
// the scene uses, `blob` the SHA-256 of its bytes.
struct AssetRef {
  std::string name;
  std::string blob;
  bool operator==(const AssetRef&) const = default;
};

// POST /lease
struct LeaseRequest {
  std::string worker_id;
  // SHA-256 of the worker's renderer executable: identical tasks it already
  // rendered are not rendered again. Empty: not sent, nothing is reused.
  std::string renderer;
};

// The leased task's place in its job.
struct LeasedTask {
  int64_t id = 0;
  int64_t job_id = 0;
  int frame = 0;
  int sample_begin = 0, sample_end = 0;
  int attempt = 0;  // 1 for the first
};

// 200 answer to POST /lease (204 without a body: nothing to do).
struct LeaseResponse {
  std::string lease_id;  // fencing token: every later call carries it
  double expiry = 0;     // the server's clock, seconds
  double lease_seconds = 0;
  std::string scene;  // blob
  int spp = 0;        // the frame's samples (the most a pixel takes, with a noise target)
  std::vector<AssetRef> assets;
  LeasedTask task;
  // This task's share of its frame's render budget (jobs/render_budget.h),
  // passed to `vesper render` as --noise-target, --min-spp, --time-limit;
  // each left out when unset.
  std::optional<double> noise_target;
  std::optional<int> min_spp;
  std::optional<double> time_limit;
  // The job's render overrides (`vesper render --aov a,b --layer-variance
  // --seed S --scale X --half`); each left out when unset.
  std::vector<std::string> aovs;
  bool layer_variance = false;
  std::optional<uint64_t> seed;
  std::optional<double> scale;
  bool half = false;
  // Seconds the render may take: the worker kills it after that and fails
  // the attempt (the job's task_timeout, else the server's default; left out
  // when neither is set).
  std::optional<double> task_timeout;
};

// POST /heartbeat
struct HeartbeatRequest {
  std::string lease_id;
  double progress = 0;  // 0..1
};
// "keep_running" (the lease is extended; a paused job's running tasks
// finish) or "stop" (the job was canceled: kill the render, drop the task).
enum class HeartbeatAnswer { KeepRunning, Stop };
struct HeartbeatResponse {
  HeartbeatAnswer answer = HeartbeatAnswer::KeepRunning;
};

// POST /complete: the result blob is uploaded first.
struct CompleteRequest {
  std::string lease_id;
  std::string result;  // SHA-256 of the result blob
  // Tail of the render's log, kept as the task's log (the server keeps the
  // last 16 KiB); optional: a worker that sends none still completes.
  std::string log;
};

// POST /fail
struct FailRequest {
  std::string lease_id;
  std::string log;  // tail of the render's log; the server keeps the last 64 KiB
};

// {"ok": true}: the answer to /complete and /fail.
struct OkResponse {
  bool ok = true;
};

VESPER_JSON_CONVERSIONS(RegisterRequest);
VESPER_JSON_CONVERSIONS(RegisterResponse);
VESPER_JSON_CONVERSIONS(AssetRef);
VESPER_JSON_CONVERSIONS(LeaseRequest);
VESPER_JSON_CONVERSIONS(LeasedTask);
VESPER_JSON_CONVERSIONS(LeaseResponse);
VESPER_JSON_CONVERSIONS(HeartbeatRequest);
VESPER_JSON_CONVERSIONS(HeartbeatAnswer);
VESPER_JSON_CONVERSIONS(HeartbeatResponse);
VESPER_JSON_CONVERSIONS(CompleteRequest);
VESPER_JSON_CONVERSIONS(FailRequest);
VESPER_JSON_CONVERSIONS(OkResponse);

}  // namespace vesper::protocol
