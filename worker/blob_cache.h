#pragma once
// The worker's verified blob cache: a blob is used only if its file still
// hashes to its name; otherwise it is downloaded into cache_dir/tmp/, hashed
// and renamed into place only when the hash matches, so an entry is never
// half written and several workers may share one cache dir.
#include <filesystem>
#include <string>

#include "worker/lease_retry.h"
#include "worker/server_api.h"

namespace vesper::worker_detail {

class BlobCache {
 public:
  BlobCache(ServerApi& api, std::filesystem::path cache_dir)
      : api_(api), dir_(std::move(cache_dir)) {}

  struct Fetched {
    std::string problem;   // "" when `file` holds the blob
    bool gave_up = false;  // the server stayed away or in trouble (not the task's fault)
  };
  // Makes `file` hold the blob `blob` (verified), downloading it with
  // `retry`'s patience. `what` names it in the problem ("scene", "asset
  // 'cube.obj'"); `unique` makes the download's temp name unique among
  // workers sharing the cache; `task_id` labels log lines.
  Fetched fetch(const std::string& blob, const std::filesystem::path& file, const std::string& what,
                const std::string& unique, LeaseRetry& retry, int64_t task_id);

 private:
  ServerApi& api_;
  std::filesystem::path dir_;
};

}  // namespace vesper::worker_detail
