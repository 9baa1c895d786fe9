#pragma once
// Every path of the farm API, written once: the "/api/v1" prefix and the
// path templates (OpenAPI style: "{id}" is a path parameter), plus the
// filled-in paths clients ask for. docs/api/openapi.yaml documents each;
// routes.h says which method and token each takes.
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

namespace vesper::protocol {

inline constexpr std::string_view kApiPrefix = "/api/v1";

// Templates relative to kApiPrefix. /healthz and /metrics are also served at
// the root (for load balancers and Prometheus).
namespace paths {
inline constexpr std::string_view kHealthz = "/healthz";
inline constexpr std::string_view kMetrics = "/metrics";
inline constexpr std::string_view kJobs = "/jobs";
inline constexpr std::string_view kJob = "/jobs/{id}";
inline constexpr std::string_view kJobCancel = "/jobs/{id}/cancel";
inline constexpr std::string_view kJobPause = "/jobs/{id}/pause";
inline constexpr std::string_view kJobResume = "/jobs/{id}/resume";
inline constexpr std::string_view kJobRetryFailed = "/jobs/{id}/retry-failed";
inline constexpr std::string_view kTaskLog = "/jobs/{id}/tasks/{task}/log";
inline constexpr std::string_view kFrames = "/jobs/{id}/frames";
inline constexpr std::string_view kFrame = "/jobs/{id}/frames/{frame}";
inline constexpr std::string_view kWorkers = "/workers";
inline constexpr std::string_view kWorkerRegister = "/workers/register";
inline constexpr std::string_view kLease = "/lease";
inline constexpr std::string_view kHeartbeat = "/heartbeat";
inline constexpr std::string_view kComplete = "/complete";
inline constexpr std::string_view kFail = "/fail";
inline constexpr std::string_view kBlob = "/blobs/{sha256}";
// The monitor (web16): the page and its assets at the root; the login under
// the API prefix; a finished frame as a PNG thumbnail and a histogram.
inline constexpr std::string_view kMonitorPage = "/";
inline constexpr std::string_view kMonitorAsset = "/monitor/{asset}";
inline constexpr std::string_view kLogin = "/login";
inline constexpr std::string_view kLogout = "/logout";
inline constexpr std::string_view kFrameThumbnail = "/jobs/{id}/frames/{frame}/thumbnail";
inline constexpr std::string_view kFrameHistogram = "/jobs/{id}/frames/{frame}/histogram";
// ops16: a worker's goodbye when it stops cleanly; prune offline and lost workers.
inline constexpr std::string_view kWorkerGoodbye = "/workers/goodbye";
inline constexpr std::string_view kWorkersPrune = "/workers/prune";
}  // namespace paths

// The query parameter of POST /jobs that validates without creating ("1" or "true").
inline constexpr std::string_view kDryRunParam = "dry_run";
// GET /jobs/{id}: a page of the task list, the tasks with ids above
// `tasks_after` (0), at most `tasks_limit` (kMaxTaskPage) of them; the answer's
// `tasks_next` is the `tasks_after` of the next page, absent on the last.
inline constexpr std::string_view kTasksAfterParam = "tasks_after";
inline constexpr std::string_view kTasksLimitParam = "tasks_limit";
inline constexpr int kMaxTaskPage = 10000;
// Response headers: the frame's blob (GET .../frames/{frame}).
inline constexpr std::string_view kBlobHeader = "X-Vesper-Blob";
// The monitor's session cookie (HttpOnly, SameSite=Strict), and the header a
// state-changing request authorised by that cookie must carry (a cross-site
// form cannot set it) with the value kMonitorHeaderValue.
inline constexpr std::string_view kSessionCookie = "vesper_session";
inline constexpr std::string_view kMonitorHeader = "X-Vesper-Monitor";
inline constexpr std::string_view kMonitorHeaderValue = "1";

// kApiPrefix + `relative` ("/jobs" -> "/api/v1/jobs").
std::string api(std::string_view relative);

// `path_template` with its {parameters} replaced, in order, by `values`.
// Throws std::invalid_argument when the counts differ.
std::string expand(std::string_view path_template, std::initializer_list<std::string_view> values);

// What a job action does; each has its own path (kJobCancel...).
enum class JobAction { Cancel, Pause, Resume, RetryFailed };
std::string_view action_template(JobAction action);
std::string_view action_name(JobAction action);  // "cancel", ..., "retry-failed"

// Filled-in paths relative to kApiPrefix, for clients.
std::string job_path(int64_t job);
std::string job_action_path(int64_t job, JobAction action);
std::string task_log_path(int64_t job, int64_t task);
std::string frames_path(int64_t job);
std::string frame_path(int64_t job, int frame);
std::string blob_path(std::string_view sha256);

}  // namespace vesper::protocol
