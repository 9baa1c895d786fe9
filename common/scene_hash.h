#pragma once
// A scene's content hash (`vesper:scene_hash` in every image the renderer
// writes): FNV-1a 64 of the scene's canonical JSON text (sorted keys, no
// whitespace) and then the bytes of every file it references, each
// length-prefixed. The renderer computes it while it loads a scene; the farm
// server computes it from a job's scene blob and assets to check that a
// worker's result is of the task's scene. One definition, so both agree.
//
// FNV, not a cryptographic hash: the hash tells scenes apart for caching and
// metadata; it does not resist an adversary (blobs are addressed by sha256).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vesper {

class SceneHash {
 public:
  explicit SceneHash(const nlohmann::json& doc);  // starts with the canonical text
  void add_file(const std::string& bytes);        // the next referenced file
  std::string hex() const;                        // 16 lower-case hex digits

 private:
  void add_sized(const std::string& s);
  uint64_t h_ = 0xcbf29ce484222325ull;
};

// The `file` values of a scene document in the order the scene loader
// hashes them: each shape's (mesh files, in array order), each light's
// (environment images, in array order), then each medium's (VDB files, in
// name order). Values that are not strings are skipped (the loader refuses
// such a scene anyway).
std::vector<std::string> hashed_file_references(const nlohmann::json& doc);

// A scene over time has one state per frame (docs/scene-format.md, "Scene
// hash"): the document of frame `frame`, every keyframed value evaluated at
// it (common/keyframes.h; `doc` itself when nothing is keyed), with `####`
// file patterns left as written. Throws JsonError naming `file` for bad keys.
nlohmann::json frame_document(const nlohmann::json& doc, double frame, const std::string& file);

// The files frame `frame` of a frame document reads: hashed_file_references
// with each '#' run filled with the frame (common/frame_pattern.h).
std::vector<std::string> frame_file_references(const nlohmann::json& frame_doc, long frame);

// Whether the scene changes over frames: keyframes or a per-frame file.
bool is_animated(const nlohmann::json& doc);

// What a shutter adds to a keyed frame's state (docs/scene-format.md, "Scene
// hash"): two frames alike at the frame but not over their shutters are
// different scenes. The document evaluated at the shutter's open and close
// (frame + render.shutter), at every key strictly inside, and — when any key
// is smooth — at 8 evenly spaced times between: enough to tell apart any two
// piecewise-linear or piecewise-cubic motions in practice. Times are not
// included, so two frames with the same motion share a state. null when the
// scene has no keys or the frame document no shutter [open, close].
nlohmann::json shutter_state(const nlohmann::json& doc, double frame, const std::string& file);

// `hash` (of the frame document and its files) extended by a non-null
// shutter_state: the renderer's vesper:scene_hash and the server's check agree.
std::string hash_with_shutter(const std::string& hash, const nlohmann::json& state);

}  // namespace vesper
