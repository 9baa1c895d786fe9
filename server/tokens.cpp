#include "server/tokens.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "common/secret_token.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {

[[noreturn]] void sys_fail(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}

Tokens read_tokens(const fs::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) sys_fail("stat " + file.string());
  if (st.st_mode & 077) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", unsigned(st.st_mode & 07777));
    throw std::runtime_error("token file " + file.string() + " has mode " + mode +
                             ": it must not be readable by group or others (chmod 600 it)");
  }
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    const auto j = nlohmann::json::parse(ss.str());
    Tokens t{j.at("submitter").get<std::string>(), j.at("worker").get<std::string>()};
    if (t.submitter.size() < 32 || t.worker.size() < 32 || t.submitter == t.worker)
      throw std::runtime_error("tokens must be distinct and at least 32 characters");
    return t;
  } catch (const std::exception& e) {
    throw std::runtime_error("token file " + file.string() +
                             " is not {\"submitter\": \"...\", \"worker\": \"...\"}: " + e.what());
  }
}

}  // namespace

Tokens load_or_create_tokens(const fs::path& file) {
  if (fs::exists(file)) return read_tokens(file);
  Tokens t{random_hex(32), random_hex(32)};
  const std::string text =
      nlohmann::json{{"submitter", t.submitter}, {"worker", t.worker}}.dump(2) + "\n";
  const fs::path tmp = file.string() + ".tmp." + random_hex(8);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) sys_fail("create " + tmp.string());
  const bool ok = ::write(fd, text.data(), text.size()) == ssize_t(text.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) {
    ::unlink(tmp.c_str());
    sys_fail("write " + tmp.string());
  }
  // link() fails with EEXIST if another server created the file meanwhile:
  // then theirs wins and is read back.
  const int rc = ::link(tmp.c_str(), file.c_str());
  const int err = errno;
  ::unlink(tmp.c_str());
  if (rc != 0) {
    if (err == EEXIST) return read_tokens(file);
    errno = err;
    sys_fail("create " + file.string());
  }
  return t;
}

}  // namespace vesper
