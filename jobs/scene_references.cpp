#include "jobs/scene_references.h"

#include "common/control_characters.h"
#include "common/json_reader.h"
#include "common/scene_reference.h"
#include "common/utf8.h"

namespace vesper {
namespace {

void collect(const nlohmann::json& node, const std::string& path, std::vector<FileReference>& out) {
  if (node.is_object()) {
    for (const auto& [key, value] : node.items()) {
      const std::string child = json_pointer_append(path, key);
      if (key == "file" && value.is_string())
        out.push_back({child, value.get<std::string>()});
      else
        collect(value, child, out);
    }
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i) collect(node[i], json_pointer_append(path, i), out);
  }
}

}  // namespace

std::vector<FileReference> scene_file_references(const nlohmann::json& scene) {
  std::vector<FileReference> out;
  collect(scene, "", out);
  return out;
}

std::optional<std::string> outside_reference(const nlohmann::json& scene) {
  for (const FileReference& r : scene_file_references(scene))
    if (const std::string why = outside_reference_problem(r.file); !why.empty())
      return r.json_path + ": '" + escape_control_characters(utf8_safe(r.file, 200)) + "' " + why;
  return std::nullopt;
}

}  // namespace vesper
