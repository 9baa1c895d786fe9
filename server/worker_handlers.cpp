#include "server/handlers.h"

#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include "common/control_characters.h"
#include "common/utf8.h"
#include "protocol/fields.h"
#include "protocol/job_messages.h"
#include "protocol/worker_messages.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/frame_noise.h"
#include "server/lease_tracker.h"
#include "server/locked_store.h"
#include "server/metrics.h"
#include "server/requests.h"
#include "server/result_check.h"
#include "server/server_clock.h"
#include "server/worker_registry.h"

namespace vesper {
namespace {

using protocol::Endpoint;
namespace f = protocol::field;

constexpr size_t kMaxLogTail = 64 * 1024;      // of a failure's log: why it failed
constexpr size_t kMaxDoneLogTail = 16 * 1024;  // of a done task's: every task keeps one

[[noreturn]] void stale(const std::string& lease_id) {
  throw ApiError(409,
                 "stale lease '" + utf8_safe(lease_id, 80) +
                     "': it expired, was re-leased, or its task was canceled; drop the task",
                 std::string("/") + f::kLeaseId);
}

ApiResponse ok() { return json_response(200, protocol::OkResponse{}); }

ApiResponse register_worker(const WorkerHandlerDeps& d, const ApiRequest& req) {
  const auto r = read_register_request(req.body);
  const std::string id = d.workers.add(r.name, d.clock.now(), r.worker_id);
  spdlog::info("worker '{}' {} as {}", escape_control_characters(r.name),
               id == r.worker_id ? "registered again" : "registered", id);
  return json_response(200, protocol::RegisterResponse{id});
}

// Each worker with its state (online, offline, lost), the task it holds a
// live lease on and the jobs it is blocked for.
ApiResponse list(const WorkerHandlerDeps& d, const ApiRequest&) {
  std::map<std::string, int> leases = d.leases.leases_by_worker();
  const auto tasks = d.leases.task_by_worker();
  std::map<std::string, std::vector<int64_t>> blocked;
  for (const auto& [worker, job] : d.store.read([](const JobStore& s) { return s.blocklists(); }))
    blocked[worker].push_back(job);
  protocol::WorkerList out;
  out.now = d.clock.now();
  for (const WorkerInfo& w : d.workers.list()) {
    protocol::WorkerInfo info{w.id,         w.name,
                              w.registered, w.last_seen,
                              leases[w.id], to_string(worker_state(w, out.now, d.lease_seconds)),
                              {},           {}};
    if (auto it = tasks.find(w.id); it != tasks.end())
      info.current_task = protocol::WorkerTask{it->second.first, it->second.second};
    info.blocklisted_for = blocked[w.id];
    out.workers.push_back(std::move(info));
  }
  return json_response(200, out);
}

ApiResponse lease(const WorkerHandlerDeps& d, const ApiRequest& req) {
  const auto r = read_lease_request(req.body);
  const double t = d.clock.now();
  if (!d.workers.touch(r.worker_id, t))
    throw ApiError(404,
                   "unknown worker '" + utf8_safe(r.worker_id, 80) + "': register first (POST " +
                       protocol::api(protocol::paths::kWorkerRegister) + ")",
                   std::string("/") + f::kWorkerId);
  int reused = 0;
  // The renderer's identity (sha256 of its executable): identical tasks done
  // by the same renderer are not rendered again — only for builds the
  // operator registered: one worker's word is no reason to hand its results
  // to other jobs. An unregistered build renders without reuse, either way.
  const std::string renderer = d.trusted_renderer(r.renderer) ? r.renderer : std::string();
  const std::optional<Lease> l =
      d.store.with([&](JobStore& s) { return s.lease(r.worker_id, t, renderer, &reused); });
  if (reused > 0) {
    d.counters.tasks_reused(reused);
    d.tasks_completed();  // reused tasks may have finished frames of several tasks
  }
  if (!l) {
    ApiResponse none;
    none.status = 204;
    return none;
  }
  d.counters.lease_granted();
  d.leases.granted(l->lease_id, l->task.id, r.worker_id, l->expiry, l->task.job_id);
  protocol::LeaseResponse out;
  out.lease_id = l->lease_id;
  out.expiry = l->expiry;
  out.lease_seconds = d.lease_seconds;
  out.scene = l->scene;
  out.spp = l->spp;
  for (const Asset& a : l->assets) out.assets.push_back({a.name, a.blob});
  const Task& task = l->task;
  out.task = {task.id, task.job_id, task.frame, task.sample_begin, task.sample_end, task.attempts};
  out.noise_target = l->budget.noise_target;
  out.min_spp = l->budget.min_spp;
  out.time_limit = l->budget.time_limit;
  out.aovs = l->overrides.aovs;
  out.layer_variance = l->overrides.layer_variance;
  out.seed = l->overrides.seed;
  out.scale = l->overrides.scale;
  out.half = l->overrides.half;
  out.task_timeout = l->task_timeout;
  if (!out.task_timeout && d.default_task_timeout > 0) out.task_timeout = d.default_task_timeout;
  return json_response(200, out);
}

ApiResponse heartbeat(const WorkerHandlerDeps& d, const ApiRequest& req) {
  const auto r = read_heartbeat_request(req.body);
  const double t = d.clock.now();
  const HeartbeatAnswer a = d.store.with([&](JobStore& s) { return s.heartbeat(r.lease_id, t); });
  d.leases.note(r.lease_id, t, a != HeartbeatAnswer::KeepRunning, r.progress);
  if (a == HeartbeatAnswer::StaleLease) stale(r.lease_id);
  return json_response(200, protocol::HeartbeatResponse{a == HeartbeatAnswer::KeepRunning
                                                            ? protocol::HeartbeatAnswer::KeepRunning
                                                            : protocol::HeartbeatAnswer::Stop});
}

// Refuses (400, the attempt failed: the worker's fault) a result that is not
// a readable render of the lease's task (server/result_check.h).
void verify_result(const WorkerHandlerDeps& d, const protocol::CompleteRequest& r,
                   const std::filesystem::path& file) {
  const auto lease = d.store.with([&](JobStore& s) { return s.current_lease(r.lease_id); });
  if (!lease) stale(r.lease_id);
  std::string problem;
  try {
    problem = check_result(file, d.expectations->of(*lease));
  } catch (const std::exception& e) {
    problem = std::string("it cannot be checked: ") + e.what();
  }
  if (problem.empty()) return;
  const std::string message =
      "result " + r.result + " of task " + std::to_string(lease->task.id) + " refused: " + problem;
  spdlog::warn("worker '{}': {}", lease->task.worker, message);
  const double t = d.clock.now();
  d.store.with([&](JobStore& s) { return s.fail(r.lease_id, "server: " + message, t); });
  d.leases.note(r.lease_id, t, true);
  throw ApiError(400, message, std::string("/") + f::kResult);
}

ApiResponse complete(const WorkerHandlerDeps& d, const ApiRequest& req) {
  auto r = read_complete_request(req.body);
  r.log = utf8_tail(r.log, kMaxDoneLogTail);
  const auto result_file = d.blobs.file(r.result);
  if (!result_file)
    throw ApiError(400,
                   "no blob " + r.result + ": upload the result first (PUT " +
                       protocol::api(protocol::paths::kBlob) + ")",
                   std::string("/") + f::kResult);
  if (d.expectations) verify_result(d, r, *result_file);
  // Read before the completion, so a one-task frame is never seen done
  // without its noise (a partial is not an EXR: read as saying nothing).
  const FrameNoise noise = read_frame_noise(*result_file);
  const double uploaded_before = BlobStore::now();
  const double t = d.clock.now();
  const bool done =
      d.store.with([&](JobStore& s) { return s.complete(r.lease_id, r.result, t, noise, r.log); });
  d.leases.note(r.lease_id, t, true);
  if (!done) stale(r.lease_id);
  d.blobs.claim({r.result}, uploaded_before);  // the task references it now
  d.tasks_completed();  // the task may have finished a frame of several tasks
  return ok();
}

ApiResponse fail(const WorkerHandlerDeps& d, const ApiRequest& req) {
  auto r = read_fail_request(req.body);
  r.log = utf8_tail(r.log, kMaxLogTail);
  const double t = d.clock.now();
  const bool failed = d.store.with([&](JobStore& s) { return s.fail(r.lease_id, r.log, t); });
  d.leases.note(r.lease_id, t, true);
  if (!failed) stale(r.lease_id);
  return ok();
}

}  // namespace

void add_worker_handlers(HandlerTable& table, const WorkerHandlerDeps& d) {
  table[Endpoint::RegisterWorker] = [d](const ApiRequest& r) { return register_worker(d, r); };
  table[Endpoint::ListWorkers] = [d](const ApiRequest& r) { return list(d, r); };
  table[Endpoint::Lease] = [d](const ApiRequest& r) { return lease(d, r); };
  table[Endpoint::Heartbeat] = [d](const ApiRequest& r) { return heartbeat(d, r); };
  table[Endpoint::Complete] = [d](const ApiRequest& r) { return complete(d, r); };
  table[Endpoint::Fail] = [d](const ApiRequest& r) { return fail(d, r); };
}

}  // namespace vesper
