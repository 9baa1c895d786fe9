#include "server/worker_handlers.h"

#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include "protocol/fields.h"
#include "protocol/job_messages.h"
#include "protocol/worker_messages.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/json_body.h"
#include "server/lease_tracker.h"
#include "server/locked_store.h"
#include "server/metrics.h"
#include "server/requests.h"
#include "server/server_clock.h"
#include "server/worker_registry.h"

namespace vesper {
namespace {

using protocol::Endpoint;
namespace f = protocol::field;

constexpr size_t kMaxLogTail = 64 * 1024;

[[noreturn]] void stale(const std::string& lease_id) {
  throw ApiError(409,
                 "stale lease '" + lease_id.substr(0, 80) +
                     "': it expired, was re-leased, or its task was canceled; drop the task",
                 std::string("/") + f::kLeaseId);
}

ApiResponse ok() { return json_response(200, protocol::OkResponse{}); }

}  // namespace

void WorkerHandlers::add_to(HandlerTable& table) {
  table[Endpoint::RegisterWorker] = [this](const ApiRequest& r) { return register_worker(r); };
  table[Endpoint::ListWorkers] = [this](const ApiRequest& r) { return list(r); };
  table[Endpoint::Lease] = [this](const ApiRequest& r) { return lease(r); };
  table[Endpoint::Heartbeat] = [this](const ApiRequest& r) { return heartbeat(r); };
  table[Endpoint::Complete] = [this](const ApiRequest& r) { return complete(r); };
  table[Endpoint::Fail] = [this](const ApiRequest& r) { return fail(r); };
}

ApiResponse WorkerHandlers::register_worker(const ApiRequest& req) {
  const auto r = read_register_request(parse_json_body(req.body));
  const std::string id = d_.workers.add(r.name, d_.clock.now());
  spdlog::info("worker '{}' registered as {}", r.name, id);
  return json_response(200, protocol::RegisterResponse{id});
}

ApiResponse WorkerHandlers::list(const ApiRequest&) {
  std::map<std::string, int> leases = d_.leases.leases_by_worker();
  protocol::WorkerList out;
  for (const WorkerInfo& w : d_.workers.list())
    out.workers.push_back({w.id, w.name, w.registered, w.last_seen, leases[w.id]});
  out.now = d_.clock.now();
  return json_response(200, out);
}

ApiResponse WorkerHandlers::lease(const ApiRequest& req) {
  const auto r = read_lease_request(parse_json_body(req.body));
  const double t = d_.clock.now();
  if (!d_.workers.touch(r.worker_id, t))
    throw ApiError(404,
                   "unknown worker '" + r.worker_id.substr(0, 80) + "': register first (POST " +
                       protocol::api(protocol::paths::kWorkerRegister) + ")",
                   std::string("/") + f::kWorkerId);
  int reused = 0;
  // The renderer's identity (sha256 of its executable): identical tasks done
  // by the same renderer are not rendered again.
  const std::optional<Lease> l =
      d_.store.with([&](JobStore& s) { return s.lease(r.worker_id, t, r.renderer, &reused); });
  if (reused > 0) {
    d_.counters.tasks_reused(reused);
    d_.tasks_completed();  // reused tasks may have finished frames of several tasks
  }
  if (!l) {
    ApiResponse none;
    none.status = 204;
    return none;
  }
  d_.counters.lease_granted();
  d_.leases.granted(l->lease_id, l->task.id, r.worker_id, l->expiry);
  protocol::LeaseResponse out{l->lease_id, l->expiry, d_.lease_seconds, l->scene, l->spp, {}, {}};
  for (const Asset& a : l->assets) out.assets.push_back({a.name, a.blob});
  const Task& task = l->task;
  out.task = {task.id,           task.job_id,     task.frame,
              task.sample_begin, task.sample_end, task.attempts + 1};
  return json_response(200, out);
}

ApiResponse WorkerHandlers::heartbeat(const ApiRequest& req) {
  const auto r = read_heartbeat_request(parse_json_body(req.body));
  const double t = d_.clock.now();
  const HeartbeatAnswer a = d_.store.with([&](JobStore& s) { return s.heartbeat(r.lease_id, t); });
  d_.leases.note(r.lease_id, t, a != HeartbeatAnswer::KeepRunning, r.progress);
  if (a == HeartbeatAnswer::StaleLease) stale(r.lease_id);
  return json_response(200, protocol::HeartbeatResponse{a == HeartbeatAnswer::KeepRunning});
}

ApiResponse WorkerHandlers::complete(const ApiRequest& req) {
  const auto r = read_complete_request(parse_json_body(req.body));
  if (!d_.blobs.exists(r.result))
    throw ApiError(400,
                   "no blob " + r.result + ": upload the result first (PUT " +
                       protocol::api(protocol::paths::kBlob) + ")",
                   std::string("/") + f::kResult);
  const double t = d_.clock.now();
  const bool done = d_.store.with([&](JobStore& s) { return s.complete(r.lease_id, r.result, t); });
  d_.leases.note(r.lease_id, t, true);
  if (!done) stale(r.lease_id);
  d_.tasks_completed();  // the task may have finished a frame of several tasks
  return ok();
}

ApiResponse WorkerHandlers::fail(const ApiRequest& req) {
  auto r = read_fail_request(parse_json_body(req.body));
  if (r.log.size() > kMaxLogTail) r.log = r.log.substr(r.log.size() - kMaxLogTail);
  const double t = d_.clock.now();
  const bool failed = d_.store.with([&](JobStore& s) { return s.fail(r.lease_id, r.log, t); });
  d_.leases.note(r.lease_id, t, true);
  if (!failed) stale(r.lease_id);
  return ok();
}

}  // namespace vesper
