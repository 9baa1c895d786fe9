// prepare_scenes (bench_runner.h): every scene checked, and its hash taken,
// before the first render, so a bad scene stops the run at once.
#include <filesystem>
#include <system_error>

#include <nlohmann/json.hpp>

#include "common/json_parse.h"
#include "common/scene_hash.h"
#include "measure/bench_runner.h"
#include "renderer/scene/scene_loader.h"

namespace vesper::measure {
namespace {

// The first file the scene reads that does not exist, or "" (the smoke VDB
// lives outside the repository and may be absent: that scene is skipped).
std::string missing_asset(const std::filesystem::path& scene_file) {
  const nlohmann::json doc = read_json_file(scene_file, "the scene file");
  const nlohmann::json frame = frame_document(doc, 1, scene_file.string());
  for (const std::string& ref : frame_file_references(frame, 1)) {
    const std::filesystem::path p = (scene_file.parent_path() / ref).lexically_normal();
    std::error_code ec;
    if (!std::filesystem::exists(p, ec)) return p.string();
  }
  return "";
}

}  // namespace

std::vector<SceneResult> prepare_scenes(const BenchSet& set, bool quick) {
  std::vector<SceneResult> out;
  for (const BenchSetScene& s : set.scenes) {
    const BenchSettings& settings = quick ? s.quick : s.full;
    SceneResult r;
    r.name = s.name;
    r.kind = s.kind;
    r.scene_path = s.path.string();
    r.width = settings.width;
    r.height = settings.height;
    r.reference_spp = settings.reference_spp;
    r.spp_ladder = settings.spp_ladder;
    try {
      if (const std::string missing = missing_asset(s.path); !missing.empty()) {
        r.skipped = true;
        r.note = "skipped: the scene reads " + missing + ", which is absent";
      } else {
        r.scene_hash = load_scene(s.path).content_hash;
      }
    } catch (const JsonError& e) {
      throw BenchSceneError(e.file(), e.json_path(), e.message());
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace vesper::measure
