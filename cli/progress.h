#pragma once
// Progress for long work: a redrawn bar with ETA on a terminal, plain lines
// (every 10%) when stderr is a pipe or a log file; nothing after
// silence_progress() (`-q`).
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace vesper::cli {

// `-q`: no progress from this process (not derived from the log level, which
// `vesper up` raises to hide its workers' chatter while its bar draws).
void silence_progress();

// 12.3s, 4m05s, 2h03m: elapsed times and ETAs as people read them.
std::string format_seconds(double seconds);

class Progress {
 public:
  explicit Progress(std::string label);
  // Thread-safe; cheap enough to call after every tile.
  void update(size_t done, size_t total);
  void finish();

 private:
  std::string label_;
  bool tty_;
  bool quiet_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  int last_decile_ = -1;
  bool finished_ = false;
};

}  // namespace vesper::cli
