#pragma once
// Downloading a job's frames (merged per frame by the server).
#include <filesystem>
#include <string>
#include <vector>

#include "cli/farm_client.h"
#include "protocol/job_messages.h"

namespace vesper::cli {

struct FetchedFrames {
  std::vector<std::filesystem::path> written;  // <dir>/<job name>.<frame, 4 digits>.exr
  std::vector<int> missing;                    // frames not ready (pending or failed)
  std::string pattern;                         // <dir>/<job name>.####.exr
};

// Writes every ready frame of `job` into `dir` (created if needed); each file
// appears complete or not at all, and is checked against its blob's sha256.
// Downloads ready `frame` of `job` to `file` (whole or not at all), checked
// against its blob's sha256. Throws FarmClientError.
void download_frame(FarmClient& client, long long job, const protocol::FrameInfo& frame,
                    const std::filesystem::path& file);

FetchedFrames fetch_frames(FarmClient& client, long long job, const std::filesystem::path& dir);

}  // namespace vesper::cli
