#include "cli/scene_package.h"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/frame_pattern.h"
#include "common/json_parse.h"
#include "common/sha256.h"
#include "jobs/scene_references.h"

namespace vesper::cli {
namespace fs = std::filesystem;
namespace {

struct Packer {
  fs::path base;
  std::string label;
  std::map<fs::path, PackedAsset> by_file;     // one asset per distinct file
  std::map<fs::path, std::string> by_pattern;  // one folder per distinct sequence
  std::vector<PackedAsset> frame_files;        // of the sequences

  // The file `ref` names, canonical; throws when it is not a readable file.
  fs::path local_file(const std::string& ref, const std::string& json_path,
                      const std::string& what) const {
    fs::path file = ref;
    if (file.is_relative()) file = base / file;
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(file, ec);
    if (ec || !fs::is_regular_file(canonical))
      throw std::runtime_error(label + ": " + json_path + ": " + what +
                               " is not a readable file (" + file.string() + ")");
    return canonical;
  }

  std::string sha_of(const fs::path& file, const std::string& json_path) const {
    const auto sha = sha256_file(file);
    if (!sha) throw std::runtime_error(label + ": " + json_path + ": cannot read " + file.string());
    return *sha;
  }

  std::string asset_for(const std::string& ref, const std::string& json_path) {
    const fs::path canonical = local_file(ref, json_path, "'" + ref + "'");
    if (auto it = by_file.find(canonical); it != by_file.end()) return it->second.name;
    const std::string sha = sha_of(canonical, json_path);
    PackedAsset a{"assets/" + sha.substr(0, 12) + "-" + canonical.filename().string(), canonical,
                  sha};
    by_file.emplace(canonical, a);
    return a.name;
  }

  // The frames' files of a sequence, in a folder named by the hash of the
  // pattern and of every packed frame's bytes: another take of the sequence
  // is another folder, and the scene's reference names the pattern in it.
  std::string sequence_for(const std::string& ref, const std::string& json_path,
                           const std::vector<int>& frames) {
    const fs::path written = fs::path(ref).is_relative() ? base / ref : fs::path(ref);
    std::error_code ec;
    const fs::path pattern = fs::weakly_canonical(written.parent_path(), ec) / written.filename();
    if (auto it = by_pattern.find(pattern); it != by_pattern.end()) return it->second;
    std::vector<PackedAsset> files;
    std::string listing = pattern.filename().string() + "\n";
    for (const int f : frames) {
      const std::string frame_ref = frame_path(ref, f).string();
      const fs::path local =
          local_file(frame_ref, json_path,
                     "frame " + std::to_string(f) + " of '" + ref + "' ('" + frame_ref + "')");
      files.push_back(
          {frame_path(pattern.filename(), f).string(), local, sha_of(local, json_path)});
      listing += std::to_string(f) + " " + files.back().sha256 + "\n";
    }
    const std::string folder = "assets/" + sha256_hex(listing).substr(0, 12) + "/";
    for (PackedAsset& a : files) {
      a.name = folder + a.name;
      frame_files.push_back(a);
    }
    return by_pattern[pattern] = folder + pattern.filename().string();
  }
};

}  // namespace

PackedScene pack_scene(const fs::path& scene_file, const std::vector<int>& frames) {
  nlohmann::json doc = read_json_file(scene_file, "the scene file");
  Packer p{fs::absolute(scene_file).parent_path(), scene_file.string(), {}, {}, {}};
  // Every "file" of the scene is an input: packed, and named by its asset.
  for (const FileReference& r : scene_file_references(doc))
    doc[nlohmann::json::json_pointer(r.json_path)] =
        has_frame_pattern(r.file) ? p.sequence_for(r.file, r.json_path, frames)
                                  : p.asset_for(r.file, r.json_path);
  PackedScene out;
  out.json = doc.dump(2) + "\n";
  for (auto& [file, asset] : p.by_file) out.assets.push_back(asset);
  out.assets.insert(out.assets.end(), p.frame_files.begin(), p.frame_files.end());
  return out;
}

}  // namespace vesper::cli
