#pragma once
// Messages of the farm's housekeeping calls (server/README.md, "Deleting jobs"
// and "Worker states"): deleting a job with the blobs it frees, a worker's
// goodbye, pruning workers that are gone. Conversions as in job_messages.h.
#include <cstdint>
#include <string>
#include <vector>

#include "protocol/json_conversions.h"

namespace vesper::protocol {

// 200 answer to DELETE /jobs/{id}: the blobs no remaining job references,
// removed with it.
struct DeleteJobResponse {
  int64_t deleted = 0;  // the job's id
  int64_t blobs_freed = 0;
  int64_t bytes_freed = 0;
};

// POST /workers/goodbye: a worker stopping cleanly (it becomes "offline").
struct GoodbyeRequest {
  std::string worker_id;
};

// 200 answer to POST /workers/prune: the ids of the offline and lost workers removed.
struct PruneResponse {
  std::vector<std::string> pruned;
};

VESPER_JSON_CONVERSIONS(DeleteJobResponse);
VESPER_JSON_CONVERSIONS(GoodbyeRequest);
VESPER_JSON_CONVERSIONS(PruneResponse);

}  // namespace vesper::protocol
