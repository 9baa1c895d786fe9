#pragma once
// Submitting a scene to the farm: validate it locally, pack and upload its
// assets and the rewritten scene as blobs, then POST /jobs.
#include <filesystem>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/farm_client.h"
#include "cli/farm_config.h"
#include "cli/job_file.h"
#include "jobs/render_budget.h"
#include "jobs/render_overrides.h"

namespace vesper::cli {

// A job request that does not fit together (min spp above max spp, a min spp
// without a noise target, ...): the message names the flag and the key.
class JobRequestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A job request from the settings' [job] defaults and a scene file.
JobRequest job_request_defaults(const FarmSettings& settings, const std::filesystem::path& scene);

// --noise-target, --min-spp, --max-spp, --time-limit over `sampling`.
void apply_sampling_flags(BudgetRequest& sampling, const SamplingFlags& flags);

// `r` with what it leaves to the scene taken from the scene's render
// settings (spp; noise target, min/max spp, time limit), checked together
// as `vesper render` checks them. Throws SceneError for a bad scene,
// JobRequestError naming the flag (--min-spp) and key (min_spp). The scene
// is loaded at `first_frame`, the job's first (a sequence need not start at 1).
JobRequest settle_job_request(JobRequest r, int first_frame);

struct Submitted {
  long long id = 0;
  int task_count = 0;
};

// Throws SceneError for a bad scene, FarmClientError for the server's refusals.
// dry_run: the server validates and creates nothing (id = 0).
Submitted submit_job(FarmClient& client, const JobRequest& request, bool dry_run = false);

}  // namespace vesper::cli
