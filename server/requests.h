#pragma once
// Reading request bodies into typed requests with the common JSON reader
// (common/json_reader.h). Every error is an ApiError 400 naming the JSON path
// (RFC 6901 pointer such as "/frames"; a missing key is named at its own
// path) and what was expected there; unknown keys are rejected, so a typo
// ("sample_per_task") is an error rather than a silently ignored default.
// Keys come from protocol/fields.h.
#include <cstdint>
#include <string>
#include <vector>

#include "jobs/job.h"
#include "protocol/ops_messages.h"
#include "protocol/worker_messages.h"

namespace vesper {

class JsonReader;

// A submitted job: {"name", "scene", "frames", "spp", "samples_per_task",
// "priority", "max_attempts", "assets", "noise_target", "min_spp", "max_spp",
// "time_limit", "aovs", "layer_variance", "seed", "scale", "half"}. `frames` is a frame-range
// string
// ("1-10x2", "1,5,9") or an array of integers; `scene` must be a SHA-256 (the
// existence of the blob is checked by the server). Limits: spp <= 1<<20, at
// most kMaxTasksPerJob tasks, kMaxAssetsPerJob assets. "assets": [{"name":
// "assets/cube.obj", "blob": "<sha256>"}, ...]: names are checked by
// asset_name_problem (jobs/job.h), unique, not "scene.json", and no name is
// the directory of another; blobs are SHA-256 spellings (their existence is
// checked by the server). Errors name "/assets/3/name" etc.
// The render budget keys "noise_target", "min_spp", "max_spp" and
// "time_limit" (jobs/render_budget.h): with max_spp the frame's spp is
// max_spp; min_spp and max_spp need a noise target, min_spp <= the frame's
// spp. Errors name the key ("/min_spp"). "task_timeout": seconds one
// render of a task may take, in (0, 30 days].
constexpr int64_t kMaxTasksPerJob = 100000;
constexpr int kMaxFrameSpp = 1 << 20;  // samples a pixel of a frame may take
constexpr int64_t kMaxAssetsPerJob = 10000;
JobSpec read_job_request(const std::string& body);
// The render budget keys of `object` (a submit body, a job file), each
// checked alone: noise_target and time_limit positive numbers, min_spp and
// max_spp integers in [1, 2^20]. Unset when absent.
BudgetRequest read_budget_request(JsonReader& object);
// The render override keys of `object` (a submit body, a job file): "aovs"
// (a non-empty list of AOV names, each known to the renderer, none twice),
// "layer_variance" (boolean), "seed" (an integer in [0, 2^63 - 1]),
// "scale" (a number in (0, 4]) and "half" (boolean). Unset when absent.
RenderOverrides read_render_overrides(JsonReader& object);
// Tasks `spec` splits into (what the store will create).
int64_t task_count(const JobSpec& spec);

// The worker protocol. Names are at most 128 characters; `renderer` and
// `result` are SHA-256 spellings; progress is in [0, 1].
protocol::RegisterRequest read_register_request(const std::string& body);
protocol::LeaseRequest read_lease_request(const std::string& body);
protocol::HeartbeatRequest read_heartbeat_request(const std::string& body);
protocol::CompleteRequest read_complete_request(const std::string& body);
protocol::FailRequest read_fail_request(const std::string& body);
// POST /workers/goodbye: {"worker_id"}.
protocol::GoodbyeRequest read_goodbye_request(const std::string& body);

}  // namespace vesper
