#pragma once
// Content-addressed blobs under <root>/ab/cdef...: the name is the SHA-256 of
// the bytes, verified on every put; a put writes a temp file, fsyncs it and
// renames it into place, so a reader never sees a partial blob and a crash
// leaves at most a stray temp file (removed at the next start).
//
// Garbage collection (collect): jobs reference blobs, but clients upload
// before they submit, so a blob put and not yet claimed by a job (its
// submit, its task's completion, its merged frame) is "pending" and kept for
// a grace period. Pending times live in memory; at start every stored blob
// younger than the grace is pending from its file's mtime until the server
// claims the referenced ones.
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vesper {

class BlobStore {
 public:
  // `grace_seconds`: how long an unclaimed blob is pending (collect's
  // grace); at start only blobs younger than that are marked.
  explicit BlobStore(std::filesystem::path root, double grace_seconds = 3600);

  // Throws ApiError 400 for a malformed hash (anything but [0-9a-f]{64}),
  // 422 when the bytes do not hash to `hash`. Returns true when the blob was
  // new, false when it already existed (idempotent).
  bool put(const std::string& hash, std::string_view bytes);
  bool exists(const std::string& hash) const;  // 400 for a malformed hash
  // The file of a stored blob, or nullopt.
  std::optional<std::filesystem::path> file(const std::string& hash) const;
  std::optional<std::uintmax_t> size(const std::string& hash) const;

  const std::filesystem::path& root() const { return root_; }

  // Wall-clock seconds (system_clock), the time base of the pending marks.
  static double now();
  // Marks a stored blob pending now, as a put does (a client's HEAD before
  // it submits without uploading). Malformed hashes are ignored.
  void mark_pending(const std::string& hash) const;
  // These blobs are referenced by a job now: not pending any more, unless
  // put again after `since` (a client uploading for its next submit).
  void claim(const std::vector<std::string>& hashes, double since) const;
  struct Freed {
    int64_t blobs = 0;
    int64_t bytes = 0;
  };
  // Removes every stored blob that is not in `referenced` and not pending
  // within `grace_seconds`. Call with the job store locked, so no job
  // references a blob between the caller's query and the removal.
  Freed collect(const std::vector<std::string>& referenced, double grace_seconds);

 private:
  std::filesystem::path path_of(const std::string& hash) const;  // validates
  void mark_pending(const std::string& hash, double at) const;
  std::filesystem::path root_;
  // The collector's bookkeeping, not the blobs: claimed through const stores too.
  mutable std::mutex pending_mutex_;
  mutable std::map<std::string, double> pending_;  // hash -> when it was last put
};

}  // namespace vesper
