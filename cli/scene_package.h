#pragma once
// Packs a scene for the farm: every file the scene references (meshes,
// environment images, VDB volumes: any "file" string in the scene JSON) becomes
// an asset with a safe relative name, and the scene is rewritten to use those
// names, so a worker with no shared filesystem renders exactly the same inputs.
// A per-frame file (`smoke.####.vdb`, common/frame_pattern.h) packs the files
// of the job's frames only, under a folder named by the sequence's hash, and
// the scene keeps the pattern: "assets/<12 hex>/smoke.####.vdb".
#include <filesystem>
#include <string>
#include <vector>

namespace vesper::cli {

struct PackedAsset {
  std::string name;             // "assets/<12 hex of sha256>-<file name>"
  std::filesystem::path local;  // the file on this machine
  std::string sha256;
};

struct PackedScene {
  std::string json;  // the rewritten scene
  std::vector<PackedAsset> assets;
};

// Throws std::runtime_error naming the scene file and the JSON path of a
// reference that cannot be read (for a sequence, the frame and its file).
// `frames` are the job's frames: those of a sequence that are packed.
PackedScene pack_scene(const std::filesystem::path& scene_file, const std::vector<int>& frames);

}  // namespace vesper::cli
