#pragma once
// The worker's verified blob cache: a blob is used only if its file still
// hashes to its name; otherwise it is downloaded into cache_dir/tmp/, hashed
// and renamed into place only when the hash matches, so an entry is never
// half written and several workers may share one cache dir.
#include <filesystem>
#include <string>

#include "worker/server_api.h"

namespace vesper::worker_detail {

class BlobCache {
 public:
  BlobCache(ServerApi& api, std::filesystem::path cache_dir)
      : api_(api), dir_(std::move(cache_dir)) {}

  // Makes `file` hold the blob `blob` (verified). `what` names it in the
  // problem ("scene", "asset 'cube.obj'"); `unique` makes the download's temp
  // name unique among workers sharing the cache. Returns the problem, or "".
  std::string fetch(const std::string& blob, const std::filesystem::path& file,
                    const std::string& what, const std::string& unique);

 private:
  ServerApi& api_;
  std::filesystem::path dir_;
};

}  // namespace vesper::worker_detail
