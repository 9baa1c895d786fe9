#include "server/handlers.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>

#include <nlohmann/json.hpp>

#include "common/json_error.h"
#include "common/json_parse.h"
#include "jobs/frame_states.h"
#include "jobs/scene_references.h"
#include "protocol/fields.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/frame_info.h"
#include "server/frame_merger.h"
#include "server/lease_tracker.h"
#include "server/locked_store.h"
#include "server/metrics.h"
#include "server/requests.h"
#include "server/server_clock.h"

namespace vesper {
namespace {

using protocol::Endpoint;
using protocol::JobAction;

protocol::JobSummary to_wire(const JobSummary& j, double now) {
  protocol::JobSummary out;
  out.id = j.id;
  out.name = j.name;
  out.priority = j.priority;
  out.state = to_string(j.state);
  out.counts = {j.queued, j.leased, j.done, j.failed, j.canceled, j.paused};
  out.total = j.total();
  out.submitted = j.submitted_at;
  out.started = j.started_at;
  out.finished = j.finished_at;
  out.eta = estimate_eta(j, now);
  return out;
}

protocol::TaskInfo to_wire(const Task& t) {
  const std::optional<double> duration =
      t.started && t.finished ? std::optional(std::max(0.0, *t.finished - *t.started))
                              : std::nullopt;
  return {t.id,       t.job_id,   t.frame,  t.sample_begin, t.sample_end, to_string(t.state),
          t.attempts, t.worker,   t.result, !t.log.empty(), std::nullopt, t.reused_from,
          t.started,  t.finished, duration};
}

// "no blob X...: upload it first", at `path` of the request body.
[[noreturn]] void missing_blob(const std::string& blob, const std::string& what,
                               const std::string& path) {
  throw ApiError(400,
                 "no blob " + blob + what + ": upload " + (what.empty() ? "the scene" : "it") +
                     " first (PUT " + protocol::api(protocol::paths::kBlob) + ")",
                 path);
}

// A scene that references a file outside its task directory (an absolute
// path, a '..' segment) would read the worker's own files: refused. A scene
// that is not JSON is left to the renderer, which fails the task saying why.
void refuse_outside_references(const BlobStore& blobs, const std::string& scene) {
  const auto file = blobs.file(scene);
  if (!file) return;
  nlohmann::json doc;
  try {
    doc = read_json_file(*file, "the scene blob");
  } catch (const JsonError&) {
    return;
  }
  if (const auto where = outside_reference(doc))
    throw ApiError(400,
                   "the scene references a file outside its directory: " + *where +
                       "; upload the file as an asset and name it by its asset name",
                   std::string("/") + protocol::field::kScene);
}

// A submitted job's scene and assets are referenced now: no longer pending
// uploads (server/blob_store.h, garbage collection).
void claim_inputs(const BlobStore& blobs, const JobSpec& spec, double since) {
  std::vector<std::string> inputs{spec.scene};
  for (const auto& a : spec.assets) inputs.push_back(a.blob);
  blobs.claim(inputs, since);
}

// The scene and asset blobs the job names must have been uploaded.
void require_blobs(const BlobStore& blobs, const JobSpec& spec) {
  namespace f = protocol::field;
  if (!blobs.exists(spec.scene)) missing_blob(spec.scene, "", std::string("/") + f::kScene);
  for (size_t i = 0; i < spec.assets.size(); ++i)
    if (!blobs.exists(spec.assets[i].blob))
      missing_blob(spec.assets[i].blob, " for asset '" + spec.assets[i].name + "'",
                   std::string("/") + f::kAssets + "/" + std::to_string(i) + "/" + f::kBlob);
}

// Each frame's state, for result reuse by frame (jobs/frame_states.h); none
// when the scene blob is missing or not JSON (reuse then keys on the blob).
std::map<int, std::string> states_of_frames(const BlobStore& blobs, const JobSpec& spec) {
  const auto file = blobs.file(spec.scene);
  if (!file) return {};
  try {
    return frame_states(read_json_file(*file, "the scene blob"), spec);
  } catch (const JsonError&) {
    return {};
  }
}

ApiResponse submit(const JobHandlerDeps& d, const ApiRequest& req) {
  JobSpec spec = read_job_request(req.body);
  const std::string dry = req.query_value(std::string(protocol::kDryRunParam));
  const bool dry_run = dry == "1" || dry == "true";
  // A dry run needs no blobs (`vesper submit --dry-run` uploads nothing); a
  // scene the server has is still checked for references outside its directory.
  if (!dry_run) require_blobs(d.blobs, spec);  // again below, under the lock
  refuse_outside_references(d.blobs, spec.scene);
  const int64_t n = task_count(spec);
  if (dry_run)
    return json_response(200, protocol::DryRunResponse{spec.name, int64_t(spec.frames.size()), n});
  spec.frame_states = states_of_frames(d.blobs, spec);
  const double uploaded_before = BlobStore::now();
  const double now = d.clock.now();
  int reused = 0;
  // Under the store's lock, as garbage collection runs: no blob checked here
  // is collected before the job references it.
  const int64_t id = d.store.with([&](JobStore& s) {
    require_blobs(d.blobs, spec);
    const int64_t job = s.submit(spec, now);
    reused = s.reuse_results(job, d.reusable_renderers, now);
    return job;
  });
  claim_inputs(d.blobs, spec, uploaded_before);
  spdlog::info("job {} '{}' submitted: {} frames, {} tasks", id, spec.name, spec.frames.size(), n);
  if (reused > 0) {
    d.counters.tasks_reused(reused);
    spdlog::info("job {}: {} of {} tasks done at once with identical tasks' results", id, reused,
                 n);
    d.tasks_completed();  // frames of several tasks to merge, outputs' noise to read
  }
  ApiResponse res = json_response(201, protocol::SubmitResponse{id, n});
  res.headers.emplace_back("Location", protocol::api(protocol::job_path(id)));
  return res;
}

ApiResponse list(const JobHandlerDeps& d, const ApiRequest&) {
  protocol::JobList out;
  out.now = d.clock.now();
  d.store.read([&](const JobStore& s) {
    for (const auto& j : s.jobs()) out.jobs.push_back(to_wire(j, out.now));
  });
  return json_response(200, out);
}

// A query parameter that must be an integer in [lo, hi] when present.
int64_t int_query(const ApiRequest& req, std::string_view key, int64_t lo, int64_t hi,
                  int64_t fallback) {
  const std::string text = req.query_value(std::string(key));
  if (text.empty()) return fallback;
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
    throw ApiError(400, "query parameter " + std::string(key) + "='" + text +
                            "': expected an integer from " + std::to_string(lo) + " to " +
                            std::to_string(hi));
  return v;
}

// One page of the task list (protocol::kTasksAfterParam): a 100 000-task job
// is read in pages, on the reading connection, so no lease waits for it.
ApiResponse get(const JobHandlerDeps& d, const ApiRequest& req) {
  const int64_t id = id_param(req, 0);
  const int64_t after = int_query(req, protocol::kTasksAfterParam, 0, INT64_MAX, 0);
  const int64_t limit =
      int_query(req, protocol::kTasksLimitParam, 1, protocol::kMaxTaskPage, protocol::kMaxTaskPage);
  protocol::JobDetail out;
  out.now = d.clock.now();
  std::vector<Task> tasks;
  std::vector<FrameStatus> frames;
  d.store.read([&](const JobStore& s) {
    out.summary = to_wire(require_job(s, id), out.now);
    tasks = s.tasks(id, after, size_t(limit) + 1);  // one more: is there a next page?
    out.blocked_workers = s.blocked_workers(id);
    if (tasks.size() > size_t(limit)) {
      tasks.pop_back();
      out.tasks_next = tasks.back().id;
    }
    // The frames of this page's tasks (ids follow frames, so a short range;
    // min and max all the same, for jobs submitted before they did).
    if (!tasks.empty()) {
      const auto [lo, hi] =
          std::minmax_element(tasks.begin(), tasks.end(),
                              [](const Task& a, const Task& b) { return a.frame < b.frame; });
      frames = s.frames(id, lo->frame, hi->frame);
    }
  });
  const std::map<int, std::string> merge_failures = d.merger.failures(id);
  for (const FrameStatus& f : frames) out.frames.push_back(frame_info(f, merge_failures));
  const std::map<int64_t, double> progress = d.leases.progress_by_task();
  for (const Task& t : tasks) {
    protocol::TaskInfo ti = to_wire(t);
    if (auto it = progress.find(t.id); t.state == TaskState::Leased && it != progress.end())
      ti.progress = it->second;
    out.tasks.push_back(std::move(ti));
  }
  return json_response(200, out);
}

ApiResponse act(const JobHandlerDeps& d, const ApiRequest& req, JobAction action) {
  const int64_t id = id_param(req, 0);
  protocol::JobActionResponse out;
  const double now = d.clock.now();
  d.store.with([&](JobStore& s) {
    require_job(s, id);
    switch (action) {
      case JobAction::Cancel:
        s.cancel(id, now);
        break;
      case JobAction::Pause:
        s.pause(id);
        break;
      case JobAction::Resume:
        s.resume(id);
        break;
      case JobAction::RetryFailed:
        out.requeued = s.retry_failed(id);
        break;
    }
    out.job = to_wire(require_job(s, id), now);
  });
  spdlog::info("job {}: {}", id, protocol::action_name(action));
  return json_response(200, out);
}

ApiResponse task_log(const JobHandlerDeps& d, const ApiRequest& req) {
  const int64_t job = id_param(req, 0);
  const int64_t task = id_param(req, 1);
  const std::vector<Task> tasks = d.store.read([&](const JobStore& s) {
    require_job(s, job);
    return s.tasks(job, task - 1, 1);
  });
  if (!tasks.empty() && tasks[0].id == task)
    return text_response(tasks[0].log, "text/plain; charset=utf-8");
  throw ApiError(404, "job " + std::to_string(job) + " has no task " + std::to_string(task));
}

}  // namespace

void add_job_handlers(HandlerTable& table, const JobHandlerDeps& d) {
  table[Endpoint::SubmitJob] = [d](const ApiRequest& r) { return submit(d, r); };
  table[Endpoint::ListJobs] = [d](const ApiRequest& r) { return list(d, r); };
  table[Endpoint::GetJob] = [d](const ApiRequest& r) { return get(d, r); };
  for (auto [endpoint, action] : {std::pair{Endpoint::CancelJob, JobAction::Cancel},
                                  std::pair{Endpoint::PauseJob, JobAction::Pause},
                                  std::pair{Endpoint::ResumeJob, JobAction::Resume},
                                  std::pair{Endpoint::RetryFailed, JobAction::RetryFailed}})
    table[endpoint] = [d, action](const ApiRequest& r) { return act(d, r, action); };
  table[Endpoint::TaskLog] = [d](const ApiRequest& r) { return task_log(d, r); };
}

}  // namespace vesper
