#pragma once
// Internal to the scene loader: the pieces of parse_scene that live in their
// own files (shapes, lights, media, transforms). Not a public header.
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/scene/json_reader.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

struct SceneParseContext {
  std::string file;                // the scene file, for messages
  std::filesystem::path base_dir;  // relative paths resolve against this
  std::vector<std::string> material_names;
  std::vector<std::filesystem::path> referenced_files;  // meshes, images and .vdb files, for the hash

  std::filesystem::path resolve(const std::string& relative) const;
  // Index of the material named by `key`; the error lists the known names.
  uint32_t material(JsonReader& node, std::string_view key) const;
};

// `T` of docs/scene-format.md: translate/rotate/scale or a row-major matrix.
Transform parse_transform(JsonReader node);
// Row-major 4x4 product a * b (apply b first).
Transform compose(const Transform& a, const Transform& b);

ShapeDesc parse_shape(JsonReader node, SceneParseContext& ctx);
LightDesc parse_light(JsonReader node, SceneParseContext& ctx);
// One entry of "media" (`name` is its key); loads and validates .vdb grids.
MediumDesc parse_medium(JsonReader node, const std::string& name, SceneParseContext& ctx);

}  // namespace vesper
