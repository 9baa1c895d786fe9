#pragma once
// The directory a task renders in: `scene.json` and the job's assets at
// their names, hard-linked from the verified blob cache (copied where a hard
// link is impossible), so the scene's relative `file` paths resolve.
#include <filesystem>
#include <string>
#include <vector>

#include "jobs/job.h"

namespace vesper::worker_detail {

// The cache file of a blob: cache_dir/<sha>.json for the scene,
// cache_dir/<sha> for an asset.
std::filesystem::path asset_cache_file(const std::filesystem::path& cache_dir,
                                       const std::string& blob);

// The directory name under cache_dir/jobs/: the scene hash when the job has
// no assets, else the SHA-256 of the scene hash and the (name, blob) list,
// so that two jobs that share a scene but not their assets never share a
// directory.
std::string task_dir_key(const std::string& scene, const std::vector<Asset>& assets);

// Makes cache_dir/jobs/<key>/ hold scene.json and the assets (all already in
// the cache and verified). It is built under cache_dir/tmp/ and renamed into
// place, so a directory is complete or absent and several workers can share
// the cache; an existing directory is reused when every file in it is the
// cached one (same inode, or the same hash). Names are checked again
// (asset_name_problem) and every resolved path must stay inside the
// directory. Returns the directory, or throws std::runtime_error.
std::filesystem::path materialise_task_dir(const std::filesystem::path& cache_dir,
                                           const std::string& scene,
                                           const std::vector<Asset>& assets,
                                           const std::string& unique);

}  // namespace vesper::worker_detail
