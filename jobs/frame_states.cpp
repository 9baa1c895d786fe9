#include "jobs/frame_states.h"

#include <algorithm>
#include <filesystem>
#include <optional>

#include "common/frame_pattern.h"
#include "common/json_error.h"
#include "common/scene_hash.h"
#include "common/sha256.h"

namespace vesper {
namespace {

// asset name (normalized, as the worker lays them out) -> blob
std::map<std::string, std::string> assets_by_name(const JobSpec& spec) {
  std::map<std::string, std::string> out;
  for (const Asset& a : spec.assets) out[normal_asset_name(a.name)] = a.blob;
  return out;
}

std::optional<std::string> state_of(const nlohmann::json& scene, int frame,
                                    const std::map<std::string, std::string>& assets) {
  const nlohmann::json doc = frame_document(scene, frame, "scene");
  std::string text = doc.dump();
  for (const std::string& ref : frame_file_references(doc, frame)) {
    const auto it = assets.find(normal_asset_name(ref));
    if (it == assets.end()) return std::nullopt;
    text += "\n" + it->second;  // the bytes, as the scene hash reads them
  }
  // Under a shutter, the motion around the frame too (as the scene hash).
  if (const nlohmann::json shutter = shutter_state(scene, frame, "scene"); !shutter.is_null())
    text += "\n" + shutter.dump();
  return sha256_hex(text);
}

// Whether `name` is a frame of the sequence `pattern` (both normalized):
// the pattern with its '#' run replaced by an optional '-' and digits.
bool is_frame_of(const std::string& name, const std::string& pattern) {
  const std::string file = std::filesystem::path(pattern).filename().string();
  const auto [pos, len] = find_frame_pattern(file);
  const size_t at = pattern.size() - file.size() + pos;  // the run in `pattern`
  const std::string prefix = pattern.substr(0, at), suffix = pattern.substr(at + len);
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, at, prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  std::string digits = name.substr(at, name.size() - at - suffix.size());
  if (digits[0] == '-') digits.erase(0, 1);
  return !digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos;
}

}  // namespace

std::vector<Asset> frame_assets(const nlohmann::json& scene, int frame,
                                const std::vector<Asset>& assets) {
  std::vector<std::string> patterns;
  for (const std::string& ref : hashed_file_references(scene))
    if (has_frame_pattern(ref)) patterns.push_back(normal_asset_name(ref));
  if (patterns.empty()) return assets;
  std::vector<Asset> out;
  for (const Asset& a : assets) {
    const std::string name = normal_asset_name(a.name);
    const bool other_frame = std::any_of(patterns.begin(), patterns.end(), [&](const auto& p) {
      return is_frame_of(name, p) && name != normal_asset_name(frame_path(p, frame).string());
    });
    if (!other_frame) out.push_back(a);
  }
  return out;
}

std::map<int, std::string> frame_states(const nlohmann::json& scene, const JobSpec& spec) {
  std::map<int, std::string> out;
  const auto assets = assets_by_name(spec);
  try {
    // A still scene has one state: computed once, not once per frame of a long job.
    const bool animated = is_animated(scene);
    std::optional<std::string> still;
    for (const int frame : spec.frames) {
      if (!animated && still) {
        out[frame] = *still;
        continue;
      }
      const auto state = state_of(scene, frame, assets);
      if (!state) return {};
      out[frame] = *state;
      if (!animated) still = state;
    }
  } catch (const JsonError&) {  // malformed keys: the renderer fails the task saying why
    return {};
  }
  return out;
}

}  // namespace vesper
