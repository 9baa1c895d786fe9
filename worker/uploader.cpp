#include "worker/uploader.h"

#include <spdlog/spdlog.h>

#include "common/sha256.h"

namespace vesper::worker_detail {

Upload upload_result(ServerApi& api, const std::filesystem::path& file, int64_t task_id,
                     LeaseRetry& retry) {
  Upload up;
  const auto sha = sha256_file(file);
  if (!sha) {
    up.problem = "cannot read " + file.string();
    return up;
  }
  const HttpResponse p =
      retry.call([&] { return api.upload_blob(*sha, file); }, "the upload of the result", task_id);
  if (p.status == 200 || p.status == 201) {
    up.blob = sha;
    return up;
  }
  up.problem = describe(p);
  up.gave_up = retry.gave_up();
  return up;
}

Completion complete_task(ServerApi& api, const std::string& lease_id, const std::string& result,
                         const std::string& log, int64_t task_id, LeaseRetry& retry) {
  const HttpResponse c = retry.call(
      [&] {
        return api.complete({lease_id, result, log});
      },
      "complete", task_id);
  if (c.status == 200) return Completion::Completed;
  if (c.status == 409) {
    spdlog::info("task {}: complete refused, lease is stale ({})", task_id, describe(c));
    return Completion::Stale;
  }
  if (retry.gave_up()) return Completion::GaveUp;
  spdlog::warn("task {}: complete refused ({})", task_id, describe(c));
  return Completion::Failed;
}

}  // namespace vesper::worker_detail
