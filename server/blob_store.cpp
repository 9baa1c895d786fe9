#include "server/blob_store.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
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

BlobStore::BlobStore(fs::path root) : root_(std::move(root)) {
  fs::create_directories(root_ / "tmp");
  // Temp files of puts interrupted by a crash are garbage.
  for (const auto& e : fs::directory_iterator(root_ / "tmp")) fs::remove(e.path());
  // Blobs of an older server were readable by everyone (0644): private now.
  const fs::perms others = fs::perms::group_all | fs::perms::others_all;
  for (const auto& e : fs::recursive_directory_iterator(root_))
    if (e.is_regular_file() && (e.status().permissions() & others) != fs::perms::none)
      fs::permissions(e.path(), fs::perms::owner_read | fs::perms::owner_write,
                      fs::perm_options::replace);
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
