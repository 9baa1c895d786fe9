#pragma once
// The noise each frame output reached, as its EXR header says
// (vesper:noise_reached, vesper:spp_mean, vesper:stop_reason; written by
// `vesper render` and `vesper merge`), read once per output and recorded in
// the job store for `vesper status` and GET /jobs/{id}. Only the header is
// read (OpenImageIO's OpenEXR reader), never the pixels.
#include <filesystem>

#include "jobs/job.h"

namespace vesper {

class BlobStore;
class LockedStore;

// What the EXR at `file` says of its noise; fields it does not carry (or a
// file that is not an OpenEXR image) are left unset.
FrameNoise read_frame_noise(const std::filesystem::path& file);

// Reads and records the noise of every frame output not read yet: outputs an
// older server recorded, and reused results of those (a completed one-task
// frame and a merge record theirs with the output). An output whose blob is
// missing is recorded as saying nothing.
// Returns how many were recorded. Thread safe; store calls are short.
// Never throws: a failure is logged and the outputs are tried again later.
int record_frame_noise(LockedStore& store, const BlobStore& blobs) noexcept;

}  // namespace vesper
