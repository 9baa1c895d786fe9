#pragma once
// Reads and validates a `vesper-scene/1` file (format: docs/scene-format.md).
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "common/json_error.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

// A rejected scene: a JsonError about a scene file (its own type so callers
// can tell a bad scene from other failures). what() reads
// "<file>: <json path>: <message>", e.g.
// "scenes/x.json: /shapes/3/radius: expected a positive number, got -1".
class SceneError : public JsonError {
 public:
  using JsonError::JsonError;
};

struct SceneLoadOptions {
  // Every file the scene references must be inside the scene's directory
  // (relative, no '..' segment): a farm task's scene must not read the
  // worker's own files (`vesper render --scene-dir-only`). Off for a local
  // render of one's own scene, where absolute paths are fine.
  bool scene_dir_only = false;
  // The time keyframed values are evaluated at (common/keyframes.h), in
  // frames: `vesper render --frame N`; 1 (the first frame) without one.
  // Per-frame files (`smoke.####.vdb`) are read at the nearest whole frame.
  double frame = 1;
};

// Loads the scene, all meshes and environment images it references. Throws
// SceneError for anything invalid, before any rendering starts.
SceneDescription load_scene(const std::filesystem::path& file,
                            const SceneLoadOptions& options = {});

// Same from the file's text (what load_scene reads): relative paths resolve
// against `file.parent_path()`, and `file` names the scene in messages.
SceneDescription parse_scene_text(const std::string& text, const std::filesystem::path& file,
                                  const SceneLoadOptions& options = {});

// Same from an already-parsed document; relative paths resolve against
// `file.parent_path()`, and `file` names the scene in messages.
SceneDescription parse_scene(const nlohmann::json& doc, const std::filesystem::path& file,
                             const SceneLoadOptions& options = {});

}  // namespace vesper
