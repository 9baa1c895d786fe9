#pragma once
// Checks a worker's result before the server commits it (POST /complete): a
// worker token is not proof that the bytes are a render of the task, and a
// committed result is reused by later identical jobs and saved by
// `vesper fetch`. A whole-frame task's result must be a readable OpenEXR
// image (header and pixels), a sample-range task's a vesper partial
// (docs/partial-format.md: magic, header, body size; its sums are checked
// when the frame is merged), and its metadata must name the task's scene
// hash, frame, sample range, frame spp and seed, and vesper:pixel_type "half"
// when the job asks for half (a worker older than the override would ignore it).
//
// Not a proof of honest pixels: a worker can still upload a valid image of
// the right metadata and wrong pixels (docs/farm.md, "Not enforced yet").
#include <climits>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "jobs/job.h"

namespace vesper {

class BlobStore;

// What a task's result must say.
struct ExpectedResult {
  std::string scene_hash;  // common/scene_hash.h of the job's scene and assets
  int frame = 0;
  int sample_begin = 0, sample_end = 0;
  int frame_spp = 0;
  uint64_t seed = 0;     // after the per-frame mixing (frame_seed)
  bool partial = false;  // a sample range of the frame, not all of it
  bool half = false;     // the job's `half` override: vesper:pixel_type must be "half"
};

// What is wrong with the result at `file` ("" when nothing is), e.g.
// "vesper:frame is '2', the task renders frame 3" or "not an OpenEXR image".
std::string check_result(const std::filesystem::path& file, const ExpectedResult& expected);

// ExpectedResult of a current lease. The scene hash of a job (its scene blob
// and assets never change) is computed once and kept: once per job for a
// still scene, once per frame for a scene over time (keys, `####` files:
// the hash of the frame's state, docs/scene-format.md "Scene hash"). Thread safe.
class ResultExpectations {
 public:
  explicit ResultExpectations(const BlobStore& blobs) : blobs_(blobs) {}
  // Throws std::runtime_error when the job's scene or an asset it references
  // cannot be read (then no render of it can be right either).
  ExpectedResult of(const Lease& lease);

 private:
  struct Scene {
    std::string hash;   // common/scene_hash.h
    uint64_t seed = 0;  // render.seed
  };
  Scene scene(const Lease& lease);
  const BlobStore& blobs_;
  std::mutex mutex_;
  // (job id, frame) -> its scene (scene and assets never change); a still
  // scene's under kEveryFrame.
  static constexpr int kEveryFrame = INT_MIN;
  std::map<std::pair<int64_t, int>, Scene> scenes_;
};

}  // namespace vesper
