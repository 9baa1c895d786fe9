#pragma once
// Submitting a scene to the farm: validate it locally, pack and upload its
// assets and the rewritten scene as blobs, then POST /jobs.
#include <filesystem>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/farm_client.h"
#include "cli/farm_config.h"
#include "jobs/render_budget.h"
#include "jobs/render_overrides.h"

namespace vesper::cli {

struct JobRequest {
  std::filesystem::path scene;
  std::string name;
  std::string frames;
  int spp = 0;  // 0 = the scene's render.spp
  int samples_per_task = 0;
  int priority = 50;
  int max_attempts = 3;
  // Noise target, min/max spp, time limit per frame; each unset = the
  // scene's render.* (docs/farm.md, "Noise targets and time limits").
  BudgetRequest sampling;
  // AOVs, per-layer variance, seed, film scale of every render (docs/farm.md,
  // "Render overrides"); unset = as the scene says.
  RenderOverrides overrides;
};

// A job request that does not fit together (min spp above max spp, a min spp
// without a noise target, ...): the message names the flag and the key.
class JobRequestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A job request from the settings' [job] defaults and a scene file.
JobRequest job_request_defaults(const FarmSettings& settings, const std::filesystem::path& scene);

// Reads a job file (format "vesper-job/1"; docs/farm.md) over `defaults`.
// Throws JsonError "<file>: <json path>: <what was expected>".
JobRequest read_job_file(const std::filesystem::path& file, JobRequest defaults);

// --noise-target, --min-spp, --max-spp, --time-limit over `sampling`.
void apply_sampling_flags(BudgetRequest& sampling, const SamplingFlags& flags);

// `r` with what it leaves to the scene taken from the scene's render
// settings (spp; noise target, min/max spp, time limit), checked together
// as `vesper render` checks them. Throws SceneError for a bad scene,
// JobRequestError naming the flag (--min-spp) and key (min_spp).
JobRequest settle_job_request(JobRequest r);

struct Submitted {
  long long id = 0;
  int task_count = 0;
};

// Throws SceneError for a bad scene, FarmClientError for the server's refusals.
// dry_run: the server validates and creates nothing (id = 0).
Submitted submit_job(FarmClient& client, const JobRequest& request, bool dry_run = false);

}  // namespace vesper::cli
