#pragma once
// A frame as the API shows it (GET /jobs/{id}/frames and the `frames` of GET
// /jobs/{id}): its state, its output and the noise the output reached.
#include <map>
#include <string>

#include "jobs/job.h"
#include "protocol/job_messages.h"

namespace vesper {

// `merge_failures`: frame -> error of the job's failed merges (FrameMerger::failures).
protocol::FrameInfo frame_info(const FrameStatus& frame,
                               const std::map<int, std::string>& merge_failures);

}  // namespace vesper
