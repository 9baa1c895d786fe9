#pragma once
// Downloading a job's frames (merged per frame by the server).
#include <filesystem>
#include <string>
#include <vector>

#include "cli/farm_client.h"

namespace vesper::cli {

struct FetchedFrames {
  std::vector<std::filesystem::path> written;  // <dir>/<job name>.<frame, 4 digits>.exr
  std::vector<int> missing;                    // frames not ready (pending or failed)
  std::string pattern;                         // <dir>/<job name>.####.exr
};

// Writes every ready frame of `job` into `dir` (created if needed); each file
// appears complete or not at all, and is checked against its blob's sha256.
FetchedFrames fetch_frames(FarmClient& client, long long job, const std::filesystem::path& dir);

}  // namespace vesper::cli
