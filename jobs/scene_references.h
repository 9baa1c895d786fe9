#pragma once
// The files a scene references: every "file": "<string>" anywhere in the
// scene document (meshes, environment images, VDB grids; docs/scene-format.md),
// with its JSON path. `vesper submit` packs them as assets; the server
// refuses a job whose scene references a file outside the task directory.
// A per-frame file (`smoke.####.vdb`) is listed as written: a '#' run
// expands to digits, so the rule holds for every frame.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vesper {

struct FileReference {
  std::string json_path;  // RFC 6901, e.g. "/media/smoke/file"
  std::string file;       // as written in the scene
};

// In document order (objects by key).
std::vector<FileReference> scene_file_references(const nlohmann::json& scene);

// The first reference that could leave the scene's directory
// (common/scene_reference.h), as "<json path>: '<file>' <why>"; nullopt when
// every reference stays inside.
std::optional<std::string> outside_reference(const nlohmann::json& scene);

}  // namespace vesper
