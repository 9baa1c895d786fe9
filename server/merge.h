#pragma once
// Merging a frame's sample-range results: `vesper merge -o OUT.exr P1 P2 ...
// -q` in a child process (posix_spawn, no shell; process/child_process.h).
#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

namespace vesper {

// The `vesper` executable to merge with: `configured` if set, else `vesper`
// next to /proc/self/exe. Empty path and `problem` set when there is none.
std::filesystem::path find_vesper_binary(const std::filesystem::path& configured,
                                         std::string& problem);

struct MergeRun {
  bool ok = false;
  bool aborted = false;  // `stop` was set: the child was killed, nothing is written
  std::string error;     // what failed, with the child's stderr tail
};

// Runs the merge into `output` (removed on failure). Polls `stop` and kills
// the child when it is set.
MergeRun run_vesper_merge(const std::filesystem::path& vesper,
                          const std::vector<std::filesystem::path>& partials,
                          const std::filesystem::path& output, const std::atomic<bool>& stop);

}  // namespace vesper
