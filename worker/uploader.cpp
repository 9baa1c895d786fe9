#include "worker/uploader.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <thread>

#include "common/sha256.h"

namespace vesper::worker_detail {
namespace {

constexpr int kTries = 3;

void pause_before_retry(int tries) {
  std::this_thread::sleep_for(std::chrono::milliseconds(200 << tries));
}

}  // namespace

Upload upload_result(ServerApi& api, const std::filesystem::path& file, int64_t task_id) {
  Upload up;
  const auto sha = sha256_file(file);
  if (!sha) {
    up.problem = "cannot read " + file.string();
    return up;
  }
  for (int tries = 0; tries < kTries; ++tries) {
    const HttpResponse p = api.upload_blob(*sha, file);
    if (p.status == 200 || p.status == 201) {
      up.blob = sha;
      return up;
    }
    up.problem = describe(p);
    spdlog::warn("task {}: upload failed ({})", task_id, up.problem);
    pause_before_retry(tries);
  }
  return up;
}

Completion complete_task(ServerApi& api, const std::string& lease_id, const std::string& result,
                         int64_t task_id) {
  for (int tries = 0; tries < kTries; ++tries) {
    const HttpResponse c = api.complete({lease_id, result});
    if (c.status == 200) return Completion::Completed;
    if (c.status == 409) {
      spdlog::info("task {}: complete refused, lease is stale ({})", task_id, describe(c));
      return Completion::Stale;
    }
    spdlog::warn("task {}: complete failed ({})", task_id, describe(c));
    if (c.status != 0 && c.status < 500) break;  // a 4xx will not get better
    pause_before_retry(tries);
  }
  return Completion::Failed;
}

}  // namespace vesper::worker_detail
