#pragma once
// A RunResult with every field set, for the report.json and history tests.
#include "regress/regress_result.h"

namespace vesper::test {

inline regress::RunResult sample_run() {
  using namespace regress;
  LayerResult beauty;
  beauty.layer = "beauty";
  beauty.verdict = Verdict::Regressed;
  beauty.reasons = {"darker in 2 tiles, worst -3.10 % at x 64-79 y 32-47 (Z -7.2)"};
  beauty.worst = {{64, 32, 16, 16, -7.2, 6e-13, 0.5, 0.4845, -0.031}};
  beauty.tiles = 12;
  beauty.significant_tiles = 2;
  beauty.max_abs_z = 7.2;
  beauty.min_detectable_change = 0.021;
  beauty.frame_detectable_change = 0.006;
  beauty.histogram_distance = 0.012;
  beauty.histogram_noise = 0.04;
  beauty.golden_nonfinite = 1;
  beauty.new_nonfinite = 3;
  beauty.introduced_nonfinite = 2;
  beauty.introduced_nonfinite_at = {{5, 6}, {7, 8}};
  beauty.has_variance = true;
  beauty.tile_size = 16;
  beauty.tiles_x = 4;
  beauty.tiles_y = 3;
  beauty.tile_z = {0.5f, -7.2f, 1, 0, 0, 0, 0, 0, 0, 0, 0, -2.5f};
  beauty.tile_significant = {0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  LayerResult fog;
  fog.layer = "fog";
  fog.reasons = {"no variance channels"};
  SceneResult cornell;
  cornell.name = "cornell";
  cornell.verdict = Verdict::Regressed;
  cornell.reasons = {"beauty: darker in 2 tiles", "channels missing: fog.A"};
  cornell.layers = {beauty, fog};
  cornell.channels_missing = {"fog.A"};
  cornell.channels_added = {"spp"};
  cornell.golden_seconds = 2.5;
  cornell.new_seconds = 2.75;
  cornell.new_seconds_repeats = {2.75, 2.7, 2.9};
  cornell.golden_image = "goldens/cornell.exr";
  cornell.new_image = "out/cornell.exr";
  SceneResult smoke;
  smoke.name = "smoke";
  smoke.verdict = Verdict::Error;
  smoke.reasons = {"no golden image goldens/smoke.exr"};
  smoke.reused = true;
  RunResult run;
  run.suite = "scenes/regression/suite.json";
  run.started_at = "2024-05-01T02:00:00Z";
  run.renderer_version = "vesper 0.13.0";
  run.server = "http://farm:8765";
  run.render_time_note = "shown, not judged: farm workers differ";
  run.verdict = Verdict::Error;
  run.scenes = {cornell, smoke};
  return run;
}

}  // namespace vesper::test
