// Deleting jobs (with the blobs no remaining job references), workers'
// goodbyes, pruning workers that are gone.
#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include "common/sha256.h"
#include "common/utf8.h"
#include "protocol/fields.h"
#include "protocol/ops_messages.h"
#include "server/api_error.h"
#include "server/blob_store.h"
#include "server/frame_views.h"
#include "server/handlers.h"
#include "server/locked_store.h"
#include "server/requests.h"
#include "server/server_clock.h"
#include "server/worker_registry.h"

namespace vesper {
namespace {

using protocol::Endpoint;

// A job with work queued or running is refused, naming its state: its
// workers would upload results nobody could find.
[[noreturn]] void busy(const JobSummary& j) {
  throw ApiError(409, "job " + std::to_string(j.id) + " is " + to_string(j.state) + " (" +
                          std::to_string(j.queued) + " queued, " + std::to_string(j.leased) +
                          " running): cancel it first (vesper delete --cancel " +
                          std::to_string(j.id) + ")");
}

ApiResponse delete_job(const HousekeepingHandlerDeps& d, const ApiRequest& req) {
  const int64_t id = id_param(req, 0);
  JobSummary refused;
  BlobStore::Freed freed;
  // One lock over the delete, the reference query and the removal: no
  // submit can reference a blob in between.
  const auto result = d.store.with([&](JobStore& s) {
    const auto r = s.delete_job(id, &refused);
    if (r == JobStore::DeleteResult::Deleted)
      freed = d.blobs.collect(s.referenced_blobs(), d.blob_grace_seconds);
    return r;
  });
  if (result == JobStore::DeleteResult::NotFound)
    throw ApiError(404, "no job " + std::to_string(id));
  if (result == JobStore::DeleteResult::Busy) busy(refused);
  if (freed.blobs > 0) {
    d.views.prune(
        [&](const std::string& blob) { return is_sha256_hex(blob) && d.blobs.exists(blob); });
  }
  spdlog::info("job {} deleted: {} blobs ({} bytes) freed", id, freed.blobs, freed.bytes);
  return json_response(200, protocol::DeleteJobResponse{id, freed.blobs, freed.bytes});
}

ApiResponse goodbye(const HousekeepingHandlerDeps& d, const ApiRequest& req) {
  const auto r = read_goodbye_request(req.body);
  if (!d.workers.goodbye(r.worker_id, d.clock.now()))
    throw ApiError(404, "unknown worker '" + utf8_safe(r.worker_id, 80) + "'",
                   std::string("/") + protocol::field::kWorkerId);
  spdlog::info("worker {} said goodbye", r.worker_id);
  return json_response(200, protocol::OkResponse{});
}

ApiResponse prune(const HousekeepingHandlerDeps& d, const ApiRequest&) {
  protocol::PruneResponse out{d.workers.prune(d.clock.now(), d.lease_seconds)};
  spdlog::info("pruned {} offline or lost workers", out.pruned.size());
  return json_response(200, out);
}

}  // namespace

void add_housekeeping_handlers(HandlerTable& table, const HousekeepingHandlerDeps& d) {
  table[Endpoint::DeleteJob] = [d](const ApiRequest& r) { return delete_job(d, r); };
  table[Endpoint::WorkerGoodbye] = [d](const ApiRequest& r) { return goodbye(d, r); };
  table[Endpoint::PruneWorkers] = [d](const ApiRequest& r) { return prune(d, r); };
}

}  // namespace vesper
