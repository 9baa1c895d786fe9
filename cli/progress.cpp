#include "cli/progress.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>

namespace vesper::cli {
namespace {
std::atomic<bool> g_silenced{false};
}  // namespace

void silence_progress() { g_silenced = true; }

Progress::Progress(std::string label)
    : label_(std::move(label)),
      tty_(::isatty(STDERR_FILENO) != 0),
      quiet_(g_silenced),
      start_(std::chrono::steady_clock::now()) {}

std::string format_seconds(double s) {
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%dh%02dm", int(s / 3600), int(s / 60) % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "%dm%02ds", int(s / 60), int(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%.1fs", s);
  return buf;
}

void Progress::update(size_t done, size_t total) {
  std::lock_guard lock(mutex_);
  if (quiet_ || finished_ || total == 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double frac = double(done) / double(total);
  const double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0;
  if (tty_) {
    if (done != total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    constexpr int kWidth = 30;
    const int filled = int(frac * kWidth);
    std::string bar(size_t(filled), '#');
    bar.resize(kWidth, '-');
    std::fprintf(stderr, "\r%s [%s] %5.1f%%  elapsed %s  eta %s   ", label_.c_str(), bar.c_str(),
                 100 * frac, format_seconds(elapsed).c_str(), format_seconds(eta).c_str());
    std::fflush(stderr);
  } else {
    const int decile = int(frac * 10);
    if (decile == last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stderr, "%s: %3d%% (elapsed %s, eta %s)\n", label_.c_str(), decile * 10,
                 format_seconds(elapsed).c_str(), format_seconds(eta).c_str());
  }
}

void Progress::finish() {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (tty_ && !quiet_) std::fprintf(stderr, "\n");
}

}  // namespace vesper::cli
