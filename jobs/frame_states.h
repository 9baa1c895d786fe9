#pragma once
// The state of each frame of a job, for result reuse: a frame whose evaluated
// scene did not change is not rendered twice, even after an edit of the scene
// that changes other frames (docs/farm.md, "Result reuse"). The server
// computes it at submit from the scene blob and the job's assets, with the
// scene hash's rules (common/scene_hash.h) but without reading any file: an
// asset is known by its blob's sha256.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jobs/job.h"

namespace vesper {

// frame -> sha256 of the frame's document (keys evaluated, `####` patterns as
// written; canonical text) and of the blob of every asset the frame reads.
// Empty when a state cannot be told for every frame — keys that do not
// evaluate, a file a frame reads that no asset holds — so that the job is
// reused only as a whole (by its scene blob), as before.
std::map<int, std::string> frame_states(const nlohmann::json& scene, const JobSpec& spec);

// The assets a task of frame `frame` needs: `assets` less the other frames'
// files of the scene's sequences (an asset whose name is a `####` reference
// with digits in place of the run, other than `frame`'s). A worker fetches
// these only, not every frame of a long sequence for each task. Everything
// else is kept (a scene that is not a document keeps all).
std::vector<Asset> frame_assets(const nlohmann::json& scene, int frame,
                                const std::vector<Asset>& assets);

}  // namespace vesper
