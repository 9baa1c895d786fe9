#include "process/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace vesper {
namespace {
using Clock = std::chrono::steady_clock;
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, size_t tail_bytes, ChildStdout out)
    : tail_bytes_(tail_bytes) {
  if (argv.empty()) throw std::invalid_argument("ChildProcess: empty argv");
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t fa;
  posix_spawnattr_t attr;
  posix_spawn_file_actions_init(&fa);
  posix_spawnattr_init(&attr);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  if (out == ChildStdout::into_tail)
    posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
  else
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 2);  // dup2 clears FD_CLOEXEC on fd 2
  // Own process group; default signal dispositions and an empty mask in the child.
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &all);
  posix_spawnattr_setflags(&attr,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const int rc = ::posix_spawn(&pid_, args[0], &fa, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  ::close(fds[1]);
  if (rc != 0) {
    ::close(fds[0]);
    pid_ = -1;
    throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
  }
  err_fd_ = fds[0];
  ::fcntl(err_fd_, F_SETFL, ::fcntl(err_fd_, F_GETFL) | O_NONBLOCK);
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !status_) {
    ::kill(pid_, SIGKILL);
    int st;
    while (::waitpid(pid_, &st, 0) < 0 && errno == EINTR) {
    }
  }
  if (err_fd_ >= 0) ::close(err_fd_);
}

void ChildProcess::drain(int timeout_ms) {
  if (err_fd_ < 0) {
    if (timeout_ms > 0) ::usleep(useconds_t(timeout_ms) * 1000);
    return;
  }
  pollfd p{err_fd_, POLLIN, 0};
  const int n = ::poll(&p, 1, timeout_ms);
  if (n <= 0) return;
  char buf[8192];
  for (;;) {
    const ssize_t r = ::read(err_fd_, buf, sizeof buf);
    if (r > 0) {
      tail_.append(buf, size_t(r));
      if (tail_.size() > 2 * tail_bytes_) tail_.erase(0, tail_.size() - tail_bytes_);
      continue;
    }
    if (r == 0) {  // EOF: the child (and anything it spawned) closed stderr
      ::close(err_fd_);
      err_fd_ = -1;
    }
    break;  // EAGAIN or error
  }
  if (tail_.size() > tail_bytes_) tail_.erase(0, tail_.size() - tail_bytes_);
}

void ChildProcess::try_reap() {
  if (status_ || pid_ <= 0) return;
  int st;
  const pid_t r = ::waitpid(pid_, &st, WNOHANG);
  if (r == pid_) status_ = st;
}

bool ChildProcess::wait_for(double seconds) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    try_reap();
    if (status_) {
      drain(0);  // whatever is left in the pipe
      while (err_fd_ >= 0) {
        const size_t before = tail_.size();
        drain(0);
        if (tail_.size() == before) break;
      }
      return true;
    }
    const auto left = std::chrono::duration<double, std::milli>(deadline - Clock::now()).count();
    if (left <= 0) return false;
    // Poll in short slices: the pipe wakes us on output, waitpid on exit.
    drain(int(std::min(left, 50.0)) + 1);
  }
}

void ChildProcess::kill(double grace_seconds) {
  if (pid_ <= 0 || status_) return;
  // The child leads its own process group: signal the group, so anything it
  // started goes too.
  if (::kill(-pid_, SIGTERM) != 0) ::kill(pid_, SIGTERM);
  if (wait_for(grace_seconds)) return;
  if (::kill(-pid_, SIGKILL) != 0) ::kill(pid_, SIGKILL);
  int st;
  while (::waitpid(pid_, &st, 0) < 0 && errno == EINTR) {
  }
  status_ = st;
  drain(0);
}

int ChildProcess::exit_code() const {
  if (!status_) return -1;
  return WIFEXITED(*status_) ? WEXITSTATUS(*status_) : -1;
}

int ChildProcess::term_signal() const {
  if (!status_) return 0;
  return WIFSIGNALED(*status_) ? WTERMSIG(*status_) : 0;
}

std::string ChildProcess::describe_status() const {
  if (!status_) return "still running";
  if (WIFEXITED(*status_)) return "exit code " + std::to_string(WEXITSTATUS(*status_));
  if (WIFSIGNALED(*status_)) {
    const int s = WTERMSIG(*status_);
    const char* name = ::strsignal(s);
    return "killed by signal " + std::to_string(s) + " (" + (name ? name : "?") + ")";
  }
  return "status " + std::to_string(*status_);
}

}  // namespace vesper
