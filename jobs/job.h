#pragma once
// The job model: a job is a scene plus frames, split into tasks of sample
// ranges; tasks move queued -> leased -> done/failed, and can be canceled or
// paused with their job. A job ends done, failed or canceled (docs/farm.md,
// "Job lifecycle").
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jobs/render_budget.h"
#include "jobs/render_overrides.h"

namespace vesper {

// A file the scene references (mesh, OpenVDB grid, environment image), sent
// as a content-addressed blob. `name` is the relative path the scene's `file`
// fields use, resolved on the worker against the directory of the scene
// (e.g. "assets/cube.obj"); `blob` is the SHA-256 of its bytes.
struct Asset {
  std::string name;
  std::string blob;
  bool operator==(const Asset& o) const { return name == o.name && blob == o.blob; }
};

// Why `name` is not an acceptable asset name, or empty when it is: a
// non-empty relative path of at most kMaxAssetNameLength bytes, made of
// '/'-separated segments that are neither empty, "." nor ".."; no backslash,
// no control character (NUL, ESC, newline, ...), not absolute. Checked by the server on submit and
// again by the worker before a name becomes a path.
constexpr size_t kMaxAssetNameLength = 255;
std::string asset_name_problem(std::string_view name);

// `name` as the worker lays the assets out ("assets/./a.obj" -> "assets/a.obj"):
// how asset names and a scene's file references are compared.
std::string normal_asset_name(std::string_view name);

struct JobSpec {
  std::string name;
  std::string scene;         // what the worker renders: a blob hash or path, opaque to the store
  std::vector<int> frames;   // from parse_frame_range
  int spp = 16;              // samples a pixel of a frame takes (at most, with a noise target)
  int samples_per_task = 0;  // 0 = the whole frame in one task
  int priority = 50;         // higher first
  int max_attempts = 3;
  std::vector<Asset> assets;  // files the scene references, in submission order
  RenderBudget budget;        // noise target, min spp, time limit of each frame
  RenderOverrides overrides;  // AOVs, per-layer variance, seed, film scale of every render
  // Seconds one render of a task may take before its worker kills it (and
  // fails the attempt); unset: the server's default.
  std::optional<double> task_timeout;
  // frame -> the frame's state (jobs/frame_states.h), set by the server at
  // submit: result reuse keys each task on it instead of on the scene blob.
  // Empty: reuse keys on the scene blob and assets (the whole job).
  std::map<int, std::string> frame_states;
};

enum class TaskState { Queued, Leased, Done, Failed, Canceled, Paused };
// Done: every task done; Failed: nothing left to run and at least one task
// failed; both are derived when the last task ends. Canceled: by the user.
enum class JobState { Active, Paused, Done, Failed, Canceled };

const char* to_string(TaskState s);
const char* to_string(JobState s);

struct Task {
  int64_t id = 0;
  int64_t job_id = 0;
  int frame = 0;
  int sample_begin = 0, sample_end = 0;
  TaskState state = TaskState::Queued;
  int attempts = 0;         // leases granted (a rendered done task has at least 1)
  std::string worker;       // current or last lease holder
  std::string result;       // set when done
  std::string log;          // tail of the last attempt's render log (done or failed)
  int64_t reused_from = 0;  // done without rendering: the identical task whose result it took
  // The last attempt: leased at `started`, ended (done, failed, expired) at
  // `finished`; the store's clock, seconds.
  std::optional<double> started, finished;
};

struct Lease {
  Task task;
  std::string lease_id;  // fencing token: every later call must carry it
  double expiry = 0;     // seconds, the store's clock
  std::string scene;
  int spp = 0;
  std::vector<Asset> assets;           // the job's assets
  RenderBudget budget;                 // this task's share of its frame's (task_budget)
  RenderOverrides overrides;           // the job's
  std::optional<double> task_timeout;  // the job's (unset: the server's default applies)
};

// What a frame's output says of its noise (its EXR's vesper:* metadata);
// unset where the output does not say (a fixed-spp render of an older
// renderer, or not an EXR).
struct FrameNoise {
  std::optional<double> noise_reached;  // RMS over pixels of the relative error of the mean
  std::optional<double> spp_mean;       // samples per pixel, averaged over the pixels
  std::string stop_reason;              // spp, noise_target, max_spp, time_limit
  bool operator==(const FrameNoise&) const = default;
};

// The state of one frame of a job: its tasks and its output (the task's
// result for a one-task frame, the merged EXR of its sample ranges
// otherwise), recorded once.
struct FrameStatus {
  int frame = 0;
  int tasks = 0, done = 0, failed = 0, canceled = 0;
  std::vector<std::string> results;  // results of the done tasks, by sample_begin
  std::string output;                // the recorded output blob, empty if none yet
  std::optional<FrameNoise> noise;   // read from the output, once it has been
  bool complete() const { return tasks > 0 && done == tasks; }
};

struct JobSummary {
  int64_t id = 0;
  std::string name;
  int priority = 0;
  JobState state = JobState::Active;
  int queued = 0, leased = 0, done = 0, failed = 0, canceled = 0, paused = 0;
  int reused = 0;                     // of the done tasks, those done without rendering
  double submitted_at = 0;            // the store's clock, seconds
  std::optional<double> started_at;   // first task leased or reused
  std::optional<double> finished_at;  // reached done, failed or canceled
  int total() const { return queued + leased + done + failed + canceled + paused; }
  bool finished() const { return queued + leased + paused == 0; }
};

// Seconds until an active job is done, estimated from the pace of its
// rendered tasks so far (remaining tasks × elapsed / rendered); nullopt when
// the job is not active or nothing was rendered yet.
std::optional<double> estimate_eta(const JobSummary& job, double now);

}  // namespace vesper
