#pragma once
// A child process started with posix_spawn (never a shell; used by the
// worker for renders and by the server for merges): stdin from
// /dev/null, stdout discarded, stderr captured into a bounded tail buffer. The
// child gets its own process group, so a terminal's Ctrl-C/SIGTERM to the
// worker's group does not kill a render the worker means to finish.
#include <sys/types.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace vesper {

// Where the child's stdout goes: discarded, or into the same tail as stderr
// (for a tool that answers on stdout, e.g. `blender --version`).
enum class ChildStdout { discard, into_tail };

class ChildProcess {
 public:
  // Throws std::runtime_error if the process cannot be started. argv[0] is a
  // path (posix_spawn: no PATH search).
  explicit ChildProcess(const std::vector<std::string>& argv, size_t tail_bytes = 64 * 1024,
                        ChildStdout out = ChildStdout::discard);
  ~ChildProcess();  // kills (SIGKILL) and reaps a child still running
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Reads stderr and reaps the child for up to `seconds`; returns true once it
  // has exited (then status() is set).
  bool wait_for(double seconds);
  // SIGTERM, then SIGKILL after `grace_seconds`; reaps.
  void kill(double grace_seconds);

  bool exited() const { return status_.has_value(); }
  // The raw waitpid status; exit_code() is -1 when killed by a signal.
  int raw_status() const { return status_.value_or(0); }
  int exit_code() const;
  int term_signal() const;              // 0 unless killed by a signal
  std::string describe_status() const;  // "exit code 2", "killed by signal 11 (Segmentation fault)"
  // stderr (and stdout with ChildStdout::into_tail), at most tail_bytes.
  const std::string& stderr_tail() const { return tail_; }
  pid_t pid() const { return pid_; }

 private:
  void drain(int timeout_ms);
  void try_reap();
  pid_t pid_ = -1;
  int err_fd_ = -1;
  size_t tail_bytes_;
  std::string tail_;
  std::optional<int> status_;
};

}  // namespace vesper
