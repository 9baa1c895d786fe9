#include "cli/scene_package.h"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/json_parse.h"
#include "common/sha256.h"

namespace vesper::cli {
namespace {

struct Packer {
  std::filesystem::path base;
  std::string label;
  std::map<std::filesystem::path, PackedAsset> by_file;  // one asset per distinct file

  std::string asset_for(const std::string& ref, const std::string& json_path) {
    std::filesystem::path file = ref;
    if (file.is_relative()) file = base / file;
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(file, ec);
    if (ec || !std::filesystem::is_regular_file(canonical))
      throw std::runtime_error(label + ": " + json_path + ": '" + ref +
                               "' is not a readable file (" + file.string() + ")");
    if (auto it = by_file.find(canonical); it != by_file.end()) return it->second.name;
    const auto sha = sha256_file(canonical);
    if (!sha) throw std::runtime_error(label + ": " + json_path + ": cannot read " + file.string());
    PackedAsset a{"assets/" + sha->substr(0, 12) + "-" + canonical.filename().string(), canonical,
                  *sha};
    by_file.emplace(canonical, a);
    return a.name;
  }

  // Every "file": "<string>" anywhere in the scene is a path to an input.
  void walk(nlohmann::json& node, const std::string& json_path) {
    if (node.is_object()) {
      for (auto& [key, value] : node.items()) {
        const std::string child = json_path + "/" + key;
        if (key == "file" && value.is_string())
          value = asset_for(value.get<std::string>(), child);
        else
          walk(value, child);
      }
    } else if (node.is_array()) {
      for (size_t i = 0; i < node.size(); ++i) walk(node[i], json_path + "/" + std::to_string(i));
    }
  }
};

}  // namespace

PackedScene pack_scene(const std::filesystem::path& scene_file) {
  nlohmann::json doc = read_json_file(scene_file, "the scene file");
  Packer p{std::filesystem::absolute(scene_file).parent_path(), scene_file.string(), {}};
  p.walk(doc, "");
  PackedScene out;
  out.json = doc.dump(2) + "\n";
  for (auto& [file, asset] : p.by_file) out.assets.push_back(asset);
  return out;
}

}  // namespace vesper::cli
