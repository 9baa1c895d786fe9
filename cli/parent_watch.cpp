#include "cli/parent_watch.h"

#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <string>

namespace vesper::cli {

void export_parent_pid() { ::setenv("VESPER_PARENT_PID", std::to_string(::getpid()).c_str(), 1); }

bool die_with_parent() {
  const char* v = std::getenv("VESPER_PARENT_PID");
  if (!v || !*v) return true;
  const long parent = std::strtol(v, nullptr, 10);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // The parent may have died before the prctl: then we were re-parented.
  return long(::getppid()) == parent;
}

}  // namespace vesper::cli
