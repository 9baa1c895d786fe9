#include "cli/scene_package.h"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/json_parse.h"
#include "common/sha256.h"
#include "jobs/scene_references.h"

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
};

}  // namespace

PackedScene pack_scene(const std::filesystem::path& scene_file) {
  nlohmann::json doc = read_json_file(scene_file, "the scene file");
  Packer p{std::filesystem::absolute(scene_file).parent_path(), scene_file.string(), {}};
  // Every "file" of the scene is an input: packed, and named by its asset.
  for (const FileReference& r : scene_file_references(doc))
    doc[nlohmann::json::json_pointer(r.json_path)] = p.asset_for(r.file, r.json_path);
  PackedScene out;
  out.json = doc.dump(2) + "\n";
  for (auto& [file, asset] : p.by_file) out.assets.push_back(asset);
  return out;
}

}  // namespace vesper::cli
