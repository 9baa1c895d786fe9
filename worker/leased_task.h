#pragma once
// One task as the server leases it (POST /lease): which scene and assets to
// fetch, which frame and sample range to render, and the lease to heartbeat.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/job.h"

namespace vesper::worker_detail {

struct LeasedTask {
  std::string lease_id, scene;
  int spp = 0, sample_begin = 0, sample_end = 0, frame = 0, attempt = 0;
  std::string id, job_id;  // as the server spells them (numbers or strings)
  double lease_seconds = 60;
  std::vector<Asset> assets;
  // A sample range that is not the whole frame renders a partial (exact
  // sample sums) for the server's `vesper merge`.
  bool partial() const { return sample_begin != 0 || sample_end != spp; }
};

// The lease answer's body; throws nlohmann::json::exception when a required
// field is missing or has the wrong type.
LeasedTask parse_lease(const nlohmann::json& answer);

}  // namespace vesper::worker_detail
