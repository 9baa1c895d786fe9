#include "server/tokens.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <spdlog/spdlog.h>

#include "common/secret_token.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {

[[noreturn]] void sys_fail(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}

void write_private_file(const fs::path& tmp, const std::string& text) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) sys_fail("create " + tmp.string());
  const bool ok = ::write(fd, text.data(), text.size()) == ssize_t(text.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) {
    ::unlink(tmp.c_str());
    sys_fail("write " + tmp.string());
  }
}

std::string tokens_text(const Tokens& t) {
  nlohmann::json j{{"submitter", t.submitter},
                   {"worker", t.worker},
                   {"shared_worker_enabled", t.shared_worker_enabled}};
  j["workers"] = nlohmann::json::object();
  for (const auto& [name, w] : t.workers)
    j["workers"][name] = {{"token", w.token}, {"enabled", w.enabled}};
  return j.dump(2) + "\n";
}

Tokens parse_tokens(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  Tokens t{j.at("submitter").get<std::string>(), j.at("worker").get<std::string>(), true, {}};
  t.shared_worker_enabled = j.value("shared_worker_enabled", true);
  if (t.submitter.size() < 32 || t.worker.size() < 32 || t.submitter == t.worker)
    throw std::runtime_error("tokens must be distinct and at least 32 characters");
  if (const auto it = j.find("workers"); it != j.end()) {
    for (const auto& [name, w] : it->items()) {
      WorkerToken wt{w.at("token").get<std::string>(), w.value("enabled", true)};
      if (wt.token.size() < 32 || wt.token == t.submitter)
        throw std::runtime_error("/workers/" + name +
                                 "/token: must be at least 32 characters and not the submitter's");
      t.workers[name] = wt;
    }
  }
  return t;
}

}  // namespace

bool Tokens::worker_allowed(const std::string& token) const {
  // Every comparison is made, in constant time, whatever matched before.
  bool ok = constant_time_equal(token, worker) && shared_worker_enabled;
  for (const auto& [name, w] : workers)
    ok = (constant_time_equal(token, w.token) && w.enabled) || ok;
  return ok;
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
    return parse_tokens(ss.str());
  } catch (const std::exception& e) {
    throw std::runtime_error(
        "token file " + file.string() +
        " is not {\"submitter\": \"...\", \"worker\": \"...\", "
        "\"workers\": {\"<name>\": {\"token\": \"...\", \"enabled\": true}}}: " +
        e.what());
  }
}

void write_tokens(const fs::path& file, const Tokens& tokens) {
  const fs::path tmp = file.string() + ".tmp." + random_hex(8);
  write_private_file(tmp, tokens_text(tokens));
  if (::rename(tmp.c_str(), file.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    errno = err;
    sys_fail("replace " + file.string());
  }
}

Tokens load_or_create_tokens(const fs::path& file) {
  if (fs::exists(file)) return read_tokens(file);
  Tokens t{random_hex(32), random_hex(32), true, {}};
  const fs::path tmp = file.string() + ".tmp." + random_hex(8);
  write_private_file(tmp, tokens_text(t));
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

TokenFile::TokenFile(fs::path file)
    : file_(std::move(file)), tokens_(std::make_shared<Tokens>(load_or_create_tokens(file_))) {
  ::stat(file_.c_str(), &seen_);
  std::ifstream in(file_);
  std::stringstream ss;
  ss << in.rdbuf();
  text_ = ss.str();
}

std::shared_ptr<const Tokens> TokenFile::current() {
  std::lock_guard lock(mutex_);
  struct stat st {};
  if (::stat(file_.c_str(), &st) != 0) return tokens_;  // gone: keep what was read
  // File times tick coarsely (a few ms) and a replaced file may get the old
  // inode number back: within a second of a change the bytes are compared too.
  const bool same_stat = st.st_ino == seen_.st_ino && st.st_size == seen_.st_size &&
                         st.st_mtim.tv_sec == seen_.st_mtim.tv_sec &&
                         st.st_mtim.tv_nsec == seen_.st_mtim.tv_nsec;
  if (same_stat && std::time(nullptr) > st.st_mtim.tv_sec + 1) return tokens_;
  seen_ = st;
  std::ifstream in(file_);
  std::stringstream ss;
  ss << in.rdbuf();
  if (ss.str() == text_) return tokens_;
  try {
    tokens_ = std::make_shared<Tokens>(read_tokens(file_));
    text_ = ss.str();
    spdlog::info("token file {} changed: re-read", file_.string());
  } catch (const std::exception& e) {
    spdlog::error("{} (the tokens read before stay in force)", e.what());
  }
  return tokens_;
}

}  // namespace vesper
