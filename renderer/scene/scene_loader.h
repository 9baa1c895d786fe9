#pragma once
// Reads and validates a `vesper-scene/1` file (format: docs/scene-format.md).
#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "renderer/scene/scene_description.h"

namespace vesper {

// A rejected scene. what() reads "<file>: <json path>: <message>", e.g.
// "scenes/x.json: /shapes/3/radius: expected a positive number, got -1".
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, std::string json_path, std::string message);
  const std::string& file() const { return file_; }
  const std::string& json_path() const { return json_path_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_, json_path_, message_;
};

// Loads the scene, all meshes and environment images it references. Throws
// SceneError for anything invalid, before any rendering starts.
SceneDescription load_scene(const std::filesystem::path& file);

// Same from an already-parsed document; relative paths resolve against
// `file.parent_path()`, and `file` names the scene in messages.
SceneDescription parse_scene(const nlohmann::json& doc, const std::filesystem::path& file);

}  // namespace vesper
