#pragma once
// The worker's last two states: upload the result as a content-addressed
// blob, then complete the task with it. Both retry what may get better
// (transport errors, 5xx) a few times.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "worker/server_api.h"

namespace vesper::worker_detail {

struct Upload {
  std::optional<std::string> blob;  // the result's sha256 once the server has it
  std::string problem;              // why not, when blob is empty
};

// PUT /blobs/<sha256 of file> (3 tries). `task_id` labels the log lines.
Upload upload_result(ServerApi& api, const std::filesystem::path& file, int64_t task_id);

enum class Completion {
  Completed,
  Stale,   // 409: another worker took over (lease expired) or the job was canceled
  Failed,  // the server did not take it (a 4xx, or 3 failed tries)
};

// POST /complete with the result blob (3 tries).
Completion complete_task(ServerApi& api, const std::string& lease_id, const std::string& result,
                         int64_t task_id);

}  // namespace vesper::worker_detail
