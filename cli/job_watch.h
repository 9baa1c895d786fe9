#pragma once
// Waiting for a farm job with a progress bar, and one-line job summaries.
#include <functional>
#include <nlohmann/json.hpp>

#include "cli/farm_client.h"

namespace vesper::cli {

// Polls GET /jobs/{id} until the job is finished (no queued, leased or paused
// task) or canceled, or no registered worker may take its queued tasks (all
// blocklisted for it: logged as an error), drawing tasks done / total on
// stderr. Logs each task that failed for good. Returns the last answer.
// `should_stop` (optional) is asked between polls: true returns at once.
nlohmann::json wait_for_job(FarmClient& client, long long job, bool show_progress = true,
                            const std::function<bool()>& should_stop = {});

// "job 3 'night-room': active, 6/6 done, 0 failed, ..."
std::string describe_job(const nlohmann::json& summary);

}  // namespace vesper::cli
