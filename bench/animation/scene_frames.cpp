// What a scene over time costs to load per frame against a still one (the
// keyframe evaluation is a pass over the JSON document before parsing), and
// the farm's per-frame states of a long shot at submit (jobs/frame_states.h).
#include <benchmark/benchmark.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "common/json_parse.h"
#include "jobs/frame_states.h"
#include "renderer/scene/scene_loader.h"

namespace {

namespace fs = std::filesystem;
const fs::path kCornell = fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/scene.json";

nlohmann::json cornell() { return vesper::read_json_file(kCornell, "the scene"); }

// The Cornell box with its camera, light and a box keyed over 240 frames
// (`keys` keys each, smooth).
nlohmann::json keyed_cornell(int keys) {
  nlohmann::json doc = cornell();
  nlohmann::json from = nlohmann::json::array(), radiance = nlohmann::json::array(),
                 angle = nlohmann::json::array();
  for (int k = 0; k < keys; ++k) {
    const double f = 1 + 239.0 * k / (keys - 1);
    from.push_back({f, {0.01 * k, 1, 3.9 - 0.01 * k}});
    radiance.push_back({f, {17 - 0.1 * k, 12, 4}});
    angle.push_back({f, 15 + k});
  }
  doc["camera"]["from"] = {{"keys", from}, {"interp", "smooth"}};
  doc["lights"][0]["radiance"] = {{"keys", radiance}, {"interp", "smooth"}};
  doc["shapes"][5]["transform"]["rotate"]["angle"] = {{"keys", angle}, {"interp", "smooth"}};
  return doc;
}

void BM_LoadStillFrame(benchmark::State& state) {
  const nlohmann::json doc = cornell();
  for (auto _ : state) benchmark::DoNotOptimize(vesper::parse_scene(doc, kCornell, {.frame = 120}));
}
BENCHMARK(BM_LoadStillFrame)->Unit(benchmark::kMicrosecond);

void BM_LoadKeyedFrame(benchmark::State& state) {
  const nlohmann::json doc = keyed_cornell(int(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(vesper::parse_scene(doc, kCornell, {.frame = 120.5}));
}
BENCHMARK(BM_LoadKeyedFrame)->Arg(4)->Arg(240)->Unit(benchmark::kMicrosecond);

// States of a 240-frame job at submit: still (one state) and keyed (240).
void BM_FrameStatesOfAShot(benchmark::State& state) {
  const nlohmann::json doc = state.range(0) ? keyed_cornell(24) : cornell();
  vesper::JobSpec spec;
  for (int f = 1; f <= 240; ++f) spec.frames.push_back(f);
  spec.assets = {{"cube.obj", std::string(64, 'a')}};
  for (auto _ : state) benchmark::DoNotOptimize(vesper::frame_states(doc, spec));
}
BENCHMARK(BM_FrameStatesOfAShot)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
