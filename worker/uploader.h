#pragma once
// The worker's last two states: upload the result as a content-addressed
// blob, then complete the task with it. Both retry what may get better (the
// server unreachable, a 5xx) for as long as the lease could live
// (lease_retry.h).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "worker/lease_retry.h"
#include "worker/server_api.h"

namespace vesper::worker_detail {

struct Upload {
  std::optional<std::string> blob;  // the result's sha256 once the server has it
  std::string problem;              // why not, when blob is empty
  bool gave_up = false;             // the server stayed away or in trouble (not the task's fault)
};

// PUT /blobs/<sha256 of file>. `task_id` labels the log lines.
Upload upload_result(ServerApi& api, const std::filesystem::path& file, int64_t task_id,
                     LeaseRetry& retry);

enum class Completion {
  Completed,
  Stale,   // 409: another worker took over (lease expired) or the job was canceled
  Failed,  // the server refused it (a 4xx)
  GaveUp,  // the server stayed away or in trouble for as long as the lease could live
};

// POST /complete with the result blob and the render's log tail.
Completion complete_task(ServerApi& api, const std::string& lease_id, const std::string& result,
                         const std::string& log, int64_t task_id, LeaseRetry& retry);

}  // namespace vesper::worker_detail
