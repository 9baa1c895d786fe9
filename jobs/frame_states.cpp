#include "jobs/frame_states.h"

#include <filesystem>
#include <optional>

#include "common/json_error.h"
#include "common/scene_hash.h"
#include "common/sha256.h"

namespace vesper {
namespace {

// asset name (normalized, as the worker lays them out) -> blob
std::map<std::string, std::string> assets_by_name(const JobSpec& spec) {
  std::map<std::string, std::string> out;
  for (const Asset& a : spec.assets)
    out[std::filesystem::path(a.name).lexically_normal().generic_string()] = a.blob;
  return out;
}

std::optional<std::string> state_of(const nlohmann::json& scene, int frame,
                                    const std::map<std::string, std::string>& assets) {
  const nlohmann::json doc = frame_document(scene, frame, "scene");
  std::string text = doc.dump();
  for (const std::string& ref : frame_file_references(doc, frame)) {
    const std::string name = std::filesystem::path(ref).lexically_normal().generic_string();
    const auto it = assets.find(name);
    if (it == assets.end()) return std::nullopt;
    text += "\n" + it->second;  // the bytes, as the scene hash reads them
  }
  // Under a shutter, the motion around the frame too (as the scene hash).
  if (const nlohmann::json shutter = shutter_state(scene, frame, "scene"); !shutter.is_null())
    text += "\n" + shutter.dump();
  return sha256_hex(text);
}

}  // namespace

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
