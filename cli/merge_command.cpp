// vesper merge — placeholder until the partial format lands (issue 6).
#include <spdlog/spdlog.h>

#include "cli/commands.h"

namespace vesper::cli {

int run_merge(const MergeCommandOptions&) {
  spdlog::error("vesper merge: partial renders are not implemented yet");
  return 2;
}

}  // namespace vesper::cli
