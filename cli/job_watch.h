#pragma once
// Waiting for a farm job with a progress bar, and one-line job summaries.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cli/farm_client.h"
#include "protocol/job_messages.h"

namespace vesper::cli {

// Polls GET /jobs/{id} until the job is finished (no queued, leased or paused
// task) or canceled, or no registered worker may take its queued tasks (all
// blocklisted for it: logged as an error), drawing tasks done / total on
// stderr. Logs each task that failed for good. Returns the last answer.
// `should_stop` (optional) is asked between polls: true returns at once.
protocol::JobDetail wait_for_job(FarmClient& client, int64_t job, bool show_progress = true,
                                 const std::function<bool()>& should_stop = {});
// The same for several jobs at once (a batch: `vesper regress --server`),
// under one progress bar named `label` (tasks of every job); returns each
// job's last answer, in the order of `jobs`.
std::vector<protocol::JobDetail> wait_for_jobs(FarmClient& client, const std::vector<int64_t>& jobs,
                                               const std::string& label, bool show_progress = true,
                                               const std::function<bool()>& should_stop = {});

// The job's frames once none is waiting for its merge on the server (frames
// whose tasks are all done may still be merging: a merge reads and writes
// the frame once, seconds), or after five minutes.
protocol::FrameList wait_for_merges(FarmClient& client, int64_t job);

// "job 3 'night-room': active, 6/6 done, 0 failed, ..."
std::string describe_job(const protocol::JobSummary& job);
// The same, plus how many tasks were reused from identical ones done before
// and the noise its finished frames reached (describe_noise).
std::string describe_job(const protocol::JobDetail& job);
// "; noise reached 0.0187 (the worst of 2 frames); 41.2 spp on average", or
// "" when no frame's output says.
std::string describe_noise(const std::vector<protocol::FrameInfo>& frames);

}  // namespace vesper::cli
