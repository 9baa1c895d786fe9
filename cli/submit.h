#pragma once
// Submitting a scene to the farm: validate it locally, pack and upload its
// assets and the rewritten scene as blobs, then POST /jobs.
#include <filesystem>
#include <optional>
#include <string>

#include "cli/farm_client.h"
#include "cli/farm_config.h"

namespace vesper::cli {

struct JobRequest {
  std::filesystem::path scene;
  std::string name;
  std::string frames;
  int spp = 0;  // 0 = the scene's render.spp
  int samples_per_task = 0;
  int priority = 50;
  int max_attempts = 3;
};

// A job request from the settings' [job] defaults and a scene file.
JobRequest job_request_defaults(const FarmSettings& settings, const std::filesystem::path& scene);

// Reads a job file (format "vesper-job/1"; docs/farm.md) over `defaults`.
// Throws JsonError "<file>: <json path>: <what was expected>".
JobRequest read_job_file(const std::filesystem::path& file, JobRequest defaults);

struct Submitted {
  long long id = 0;
  int task_count = 0;
};

// Throws SceneError for a bad scene, FarmClientError for the server's refusals.
// dry_run: the server validates and creates nothing (id = 0).
Submitted submit_job(FarmClient& client, const JobRequest& request, bool dry_run = false);

}  // namespace vesper::cli
