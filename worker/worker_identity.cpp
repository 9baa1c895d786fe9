#include "worker/worker_identity.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <system_error>

namespace vesper::worker_detail {

namespace {
constexpr int kSlots = 64;
constexpr size_t kMaxIdBytes = 64;
}  // namespace

WorkerIdentity::WorkerIdentity(const std::filesystem::path& cache_dir) {
  const std::filesystem::path dir = cache_dir / "worker-ids";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  for (int slot = 0; slot < kSlots && fd_ < 0; ++slot) {
    const std::string file = (dir / std::to_string(slot)).string();
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
    if (fd < 0) return;
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd);
      continue;
    }
    fd_ = fd;
    char buf[kMaxIdBytes];
    const ssize_t n = ::pread(fd_, buf, sizeof buf, 0);
    if (n > 0) id_.assign(buf, size_t(n));
    while (!id_.empty() && (id_.back() == '\n' || id_.back() == ' ')) id_.pop_back();
  }
}

WorkerIdentity::~WorkerIdentity() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

void WorkerIdentity::save(const std::string& id) {
  if (fd_ < 0 || id == id_ || id.size() >= kMaxIdBytes) return;
  id_ = id;
  const std::string text = id + "\n";
  if (::ftruncate(fd_, 0) == 0 && ::pwrite(fd_, text.data(), text.size(), 0) > 0) ::fsync(fd_);
}

}  // namespace vesper::worker_detail
