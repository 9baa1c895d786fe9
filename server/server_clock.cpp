#include "server/server_clock.h"

#include <algorithm>
#include <chrono>

namespace vesper {

double ServerClock::now() {
  const double t =
      source_ ? source_()
              : std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                    .count();
  std::lock_guard lock(mutex_);
  last_ = std::max(last_, t);
  return last_;
}

}  // namespace vesper
