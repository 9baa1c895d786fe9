#pragma once
// Content-addressed blobs under <root>/ab/cdef...: the name is the SHA-256 of
// the bytes, verified on every put; a put writes a temp file, fsyncs it and
// renames it into place, so a reader never sees a partial blob and a crash
// leaves at most a stray temp file (removed at the next start).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace vesper {

class BlobStore {
 public:
  explicit BlobStore(std::filesystem::path root);

  // Throws ApiError 400 for a malformed hash (anything but [0-9a-f]{64}),
  // 422 when the bytes do not hash to `hash`. Returns true when the blob was
  // new, false when it already existed (idempotent).
  bool put(const std::string& hash, std::string_view bytes);
  bool exists(const std::string& hash) const;  // 400 for a malformed hash
  // The file of a stored blob, or nullopt.
  std::optional<std::filesystem::path> file(const std::string& hash) const;
  std::optional<std::uintmax_t> size(const std::string& hash) const;

  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path path_of(const std::string& hash) const;  // validates
  std::filesystem::path root_;
};

}  // namespace vesper
