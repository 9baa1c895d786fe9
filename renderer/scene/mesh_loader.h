#pragma once
// Triangle meshes from PLY and OBJ files (through assimp). Polygons are
// triangulated; points and lines are ignored; degenerate triangles are kept
// (the renderer copes with them). Node transforms are not applied: PLY and OBJ
// have none.
#include <filesystem>
#include <string>

#include "renderer/scene/scene_description.h"

namespace vesper {

// Loads `path` into positions + triangles (in the file's own coordinates).
// Errors (missing file, unsupported extension, parse error, no triangles)
// throw SceneError naming `scene_file`, `json_path` (the "file" key) and `path`.
MeshShapeDesc load_mesh_file(const std::filesystem::path& path, const std::string& scene_file,
                             const std::string& json_path);

}  // namespace vesper
