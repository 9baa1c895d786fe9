#include "server/blob_store.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <set>
#include <system_error>

#include "common/secret_token.h"
#include "common/sha256.h"
#include "common/utf8.h"
#include "server/api_error.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {
[[noreturn]] void sys_fail(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}
}  // namespace

BlobStore::BlobStore(fs::path root, double grace_seconds) : root_(std::move(root)) {
  const double cutoff = now() - grace_seconds;
  fs::create_directories(root_ / "tmp");
  // Temp files of puts interrupted by a crash are garbage.
  for (const auto& e : fs::directory_iterator(root_ / "tmp")) fs::remove(e.path());
  // Blobs of an older server were readable by everyone (0644): private now.
  const fs::perms others = fs::perms::group_all | fs::perms::others_all;
  for (const auto& e : fs::recursive_directory_iterator(root_)) {
    if (!e.is_regular_file()) continue;
    if ((e.status().permissions() & others) != fs::perms::none)
      fs::permissions(e.path(), fs::perms::owner_read | fs::perms::owner_write,
                      fs::perm_options::replace);
    // Pending from its mtime until the server claims what jobs reference.
    const std::string hash =
        e.path().parent_path().filename().string() + e.path().filename().string();
    const auto mtime = std::chrono::file_clock::to_sys(e.last_write_time());
    const double put = std::chrono::duration<double>(mtime.time_since_epoch()).count();
    if (put > cutoff && is_sha256_hex(hash)) pending_[hash] = put;
  }
}

double BlobStore::now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

void BlobStore::mark_pending(const std::string& hash) const {
  if (is_sha256_hex(hash) && exists(hash)) mark_pending(hash, now());
}

void BlobStore::mark_pending(const std::string& hash, double at) const {
  std::lock_guard lock(pending_mutex_);
  pending_[hash] = at;
}

void BlobStore::claim(const std::vector<std::string>& hashes, double since) const {
  std::lock_guard lock(pending_mutex_);
  for (const std::string& h : hashes) {
    auto it = pending_.find(h);
    if (it != pending_.end() && it->second <= since) pending_.erase(it);
  }
}

BlobStore::Freed BlobStore::collect(const std::vector<std::string>& referenced,
                                    double grace_seconds) {
  const std::set<std::string> keep(referenced.begin(), referenced.end());
  const double cutoff = now() - grace_seconds;
  Freed freed;
  std::lock_guard lock(pending_mutex_);
  for (const auto& dir : fs::directory_iterator(root_)) {
    const std::string prefix = dir.path().filename().string();
    if (!dir.is_directory() || prefix.size() != 2) continue;  // tmp/
    for (const auto& e : fs::directory_iterator(dir.path())) {
      const std::string hash = prefix + e.path().filename().string();
      if (!e.is_regular_file() || !is_sha256_hex(hash) || keep.count(hash)) continue;
      const auto p = pending_.find(hash);
      if (p != pending_.end() && p->second > cutoff) continue;
      std::error_code size_error, remove_error;
      const auto size = e.file_size(size_error);
      if (!fs::remove(e.path(), remove_error)) continue;
      if (p != pending_.end()) pending_.erase(p);
      ++freed.blobs;
      freed.bytes += size_error ? 0 : int64_t(size);
    }
  }
  // Marks past the grace protect nothing any more (nor do referenced blobs need one).
  std::erase_if(pending_, [&](const auto& p) { return p.second <= cutoff; });
  return freed;
}

fs::path BlobStore::path_of(const std::string& hash) const {
  if (!is_sha256_hex(hash))
    throw ApiError(400, "malformed blob name '" + utf8_safe(hash, 80) +
                            "': expected a SHA-256 as 64 lower-case hex digits");
  return root_ / hash.substr(0, 2) / hash.substr(2);
}

bool BlobStore::exists(const std::string& hash) const { return fs::exists(path_of(hash)); }

std::optional<fs::path> BlobStore::file(const std::string& hash) const {
  fs::path p = path_of(hash);
  if (!fs::exists(p)) return std::nullopt;
  return p;
}

std::optional<std::uintmax_t> BlobStore::size(const std::string& hash) const {
  std::error_code ec;
  const auto n = fs::file_size(path_of(hash), ec);
  if (ec) return std::nullopt;
  return n;
}

bool BlobStore::put(const std::string& hash, std::string_view bytes) {
  const fs::path final_path = path_of(hash);
  const std::string actual = sha256_hex(bytes);
  if (actual != hash)
    throw ApiError(422, "blob content does not match its name: the body's SHA-256 is " + actual);
  mark_pending(hash, now());  // a client may submit a job with it next
  if (fs::exists(final_path)) return false;
  fs::create_directories(final_path.parent_path());
  const fs::path tmp = root_ / "tmp" / (hash + "." + random_hex(8));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) sys_fail("create " + tmp.string());
  size_t off = 0;
  while (off < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + off, bytes.size() - off);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      errno = e;
      sys_fail("write " + tmp.string());
    }
    off += size_t(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(tmp.c_str());
    sys_fail("fsync " + tmp.string());
  }
  // Two concurrent puts of the same blob both rename identical bytes: harmless.
  if (::rename(tmp.c_str(), final_path.c_str()) != 0) {
    ::unlink(tmp.c_str());
    sys_fail("rename into " + final_path.string());
  }
  // Make the rename itself durable.
  const int dfd = ::open(final_path.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return true;
}

}  // namespace vesper
