#include "cli/regress_render.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/atomic_file.h"
#include "compositor/histogram.h"
#include "compositor/layer_mix.h"
#include "jobs/frame_range.h"
#include "jobs/render_budget.h"
#include "process/child_process.h"
#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_keys.h"

namespace vesper::cli {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> render_argv(const regress::SuiteScene& scene, int frame,
                                     const fs::path& out, const RegressRenderSettings& s) {
  std::vector<std::string> argv{s.renderer.string(), "render",  scene.scene.string(),  "-o",
                                out.string(),        "--frame", std::to_string(frame), "-q"};
  auto add = [&argv](const char* flag, const std::string& value) {
    argv.push_back(flag);
    argv.push_back(value);
  };
  const RenderOverrides o = suite_render_overrides(scene, s.seed);
  add("--aov", join_aovs(o.aovs));
  if (o.layer_variance) argv.push_back("--layer-variance");
  if (o.scale) add("--scale", exact_text(*o.scale));
  if (o.seed) add("--seed", std::to_string(*o.seed));
  if (scene.spp) add("--spp", std::to_string(*scene.spp));
  if (scene.noise_target) add("--noise-target", exact_text(*scene.noise_target));
  if (s.threads) add("--threads", std::to_string(*s.threads));
  return argv;
}

}  // namespace

RenderOverrides suite_render_overrides(const regress::SuiteScene& scene,
                                       std::optional<unsigned long long> seed) {
  RenderOverrides o;
  o.aovs = {"variance"};  // the beauty's variance, and every layer's below
  o.layer_variance = true;
  o.seed = seed;
  o.scale = scene.scale;
  return o;
}

SuiteRender render_suite_frame(const regress::SuiteScene& scene, int frame,
                               const std::string& label, const RegressRenderSettings& settings) {
  SuiteRender r;
  r.label = label;
  r.exr = settings.out_dir / (label + ".exr");
  for (int i = 0; i < std::max(1, settings.repeats); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      ChildProcess child(render_argv(scene, frame, r.exr, settings));
      while (!child.wait_for(3600)) {
      }
      if (child.exit_code() != 0) {
        r.error = settings.renderer.filename().string() + " render " + scene.scene.string() +
                  " failed (" + child.describe_status() + "): " + child.stderr_tail();
        return r;
      }
    } catch (const std::runtime_error& e) {
      r.error = e.what();
      return r;
    }
    r.seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return r;
}

fs::path golden_image(const fs::path& dir, const std::string& label) {
  return dir / (label + ".exr");
}

fs::path golden_sidecar(const fs::path& dir, const std::string& label) {
  return dir / (label + ".json");
}

void write_golden(const SuiteRender& render, const fs::path& dir) {
  const LayeredImage image = read_exr(render.exr);
  auto meta = [&](const char* key) {
    const auto it = image.metadata.find(key);
    return it == image.metadata.end() ? std::string() : it->second;
  };
  const Histogram histogram =
      log2_histogram(extract_layer(image, "beauty", render.exr.string()), LumaWeights::Rec709);
  nlohmann::json sidecar{{"format", "vesper-golden/1"},
                         {"renderer_version", meta(metadata_key::kRendererVersion)},
                         {"scene_hash", meta(metadata_key::kSceneHash)},
                         {"spp", meta(metadata_key::kSpp)},
                         {"seconds_repeats", render.seconds},
                         {"histogram", histogram_to_json(histogram)}};
  // The fastest repeat: the timing check compares fastest with fastest.
  if (!render.seconds.empty())
    sidecar["seconds"] = *std::min_element(render.seconds.begin(), render.seconds.end());
  // A farm render's own time is not a local wall time: --local does not judge against it.
  if (render.on_farm) sidecar["timing"] = "farm";
  std::error_code ec;
  fs::rename(render.exr, golden_image(dir, render.label), ec);
  if (ec) {  // another file system: copy, then rename into place
    const fs::path tmp = golden_image(dir, render.label).string() + ".tmp";
    fs::copy_file(render.exr, tmp, fs::copy_options::overwrite_existing);
    fs::rename(tmp, golden_image(dir, render.label));
  }
  write_file_atomically(golden_sidecar(dir, render.label), sidecar.dump(2) + "\n");
}

std::optional<GoldenTime> golden_seconds(const fs::path& dir, const std::string& label) {
  std::ifstream f(golden_sidecar(dir, label));
  if (!f) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("seconds") || !j["seconds"].is_number()) return std::nullopt;
  return GoldenTime{j["seconds"].get<double>(), j.value("timing", "") == "farm"};
}

std::optional<double> exr_render_seconds(const fs::path& exr) {
  try {
    const auto meta = read_exr_metadata(exr);
    const auto it = meta.find(metadata_key::kRenderSeconds);
    if (it != meta.end()) return std::stod(it->second);
  } catch (const std::exception&) {  // unreadable: the comparison says so
  }
  return std::nullopt;
}

std::vector<SuiteFrame> suite_frames(const regress::Suite& suite) {
  std::vector<SuiteFrame> out;
  for (const regress::SuiteScene& s : suite.scenes) {
    const std::vector<int> frames = parse_frame_range(s.frames);  // load_suite checked it
    for (int f : frames)
      out.push_back({&s, f, frames.size() == 1 ? s.name : s.name + "." + std::to_string(f)});
  }
  return out;
}

}  // namespace vesper::cli
