#pragma once
// Downloading a job's frames (merged per frame by the server).
#include <filesystem>
#include <string>
#include <vector>

#include "cli/farm_client.h"
#include "protocol/job_messages.h"

namespace vesper::cli {

struct FetchedFrames {
  std::string stem;                            // job_file_stem of the job's name
  std::vector<std::filesystem::path> written;  // <dir>/<stem>.<frame, 4 digits>.exr
  std::vector<int> missing;                    // frames not ready (pending or failed)
  std::string pattern;                         // <dir>/<stem>.####.exr
};

// A job's name as the start of a file name inside the output folder: the name
// is whatever a submitter chose ("../../x", "/abs/dir/x", "a####"), so '/',
// '\', '#', control characters and a leading '.' become '_', invalid UTF-8
// becomes U+FFFD, it is cut to 200 bytes, and an empty name is "job-<id>".
// Nothing derived from it can leave the folder or change the frame pattern.
std::string job_file_stem(const std::string& name, long long job);

// Downloads ready `frame` of `job` to `file` (whole or not at all), checked
// against its blob's sha256. Throws FarmClientError.
void download_frame(FarmClient& client, long long job, const protocol::FrameInfo& frame,
                    const std::filesystem::path& file);

// Writes every ready frame of `job` into `dir` (created if needed); each file
// appears complete or not at all, and is checked against its blob's sha256.
FetchedFrames fetch_frames(FarmClient& client, long long job, const std::filesystem::path& dir);

}  // namespace vesper::cli
