#include "worker/blob_cache.h"

#include "common/sha256.h"

namespace fs = std::filesystem;

namespace vesper::worker_detail {

BlobCache::Fetched BlobCache::fetch(const std::string& blob, const fs::path& file,
                                    const std::string& what, const std::string& unique,
                                    LeaseRetry& retry, int64_t task_id) {
  // Checked before the name becomes a path.
  if (!is_sha256_hex(blob)) return {"the lease names a malformed " + what + " hash '" + blob + "'"};
  if (sha256_file(file) == blob) return {};
  const fs::path part = dir_ / "tmp" / (blob + "." + unique + ".part");
  const HttpResponse g = retry.call([&] { return api_.download_blob(blob, part); },
                                    "the download of the " + what, task_id);
  std::string problem;
  std::error_code ec;
  if (g.status != 200)
    problem = "download of " + what + " blob " + blob + " failed: " + describe(g);
  else if (const auto got = sha256_file(part); got != blob)
    problem = "downloaded " + what + " blob does not match its hash: expected " + blob + ", got " +
              got.value_or("(unreadable)");
  else
    fs::rename(part, file, ec);
  if (problem.empty() && ec) problem = "cannot store " + file.string() + ": " + ec.message();
  fs::remove(part, ec);
  return {problem, g.status != 200 && retry.gave_up()};
}

}  // namespace vesper::worker_detail
