#include "server/data_dir.h"

#include <fcntl.h>
#include <unistd.h>

#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace vesper {
namespace {

void set_mode(const fs::path& p, fs::perms mode) {
  std::error_code ec;
  fs::permissions(p, mode, fs::perm_options::replace, ec);
  if (ec)
    throw std::runtime_error("server: cannot make " + p.string() + " private (mode " +
                             (mode == fs::perms::owner_all ? "0700" : "0600") +
                             "): " + ec.message());
}

}  // namespace

void make_data_dir_private(const fs::path& dir) {
  fs::create_directories(dir);
  set_mode(dir, fs::perms::owner_all);
  const fs::path store = dir / "jobs.sqlite";
  if (!fs::exists(store)) {
    const int fd = ::open(store.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
    if (fd < 0)
      throw std::system_error(errno, std::generic_category(), "server: create " + store.string());
    ::close(fd);
  }
  for (const char* name : {"jobs.sqlite", "jobs.sqlite-wal", "jobs.sqlite-shm", "workers.json"})
    if (fs::exists(dir / name))
      set_mode(dir / name, fs::perms::owner_read | fs::perms::owner_write);
}

}  // namespace vesper
