// The worker's child render command line: built from the task and the worker
// config only (the scene file is never parsed for it).
#include "worker/render_command.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace vesper::worker_detail {
namespace {

protocol::LeaseResponse lease(int frame, int spp, int begin, int end) {
  protocol::LeaseResponse t;
  t.spp = spp;
  t.task.frame = frame;
  t.task.sample_begin = begin;
  t.task.sample_end = end;
  return t;
}

// The job's render overrides, which go on as `vesper render`'s own flags.
protocol::LeaseResponse with_overrides(protocol::LeaseResponse l) {
  l.aovs = {"variance", "albedo"};
  l.layer_variance = true;
  l.seed = 11;
  l.scale = 0.125;
  l.half = true;
  return l;
}

WorkerConfig config(int threads) {
  WorkerConfig c;
  c.vesper_binary = "/opt/vesper/bin/vesper";
  c.render_threads = threads;
  return c;
}

// A whole frame renders an EXR; a sample range a partial (--partial); the
// job's render overrides and the worker's --threads are passed on.
TEST(RenderCommand, FollowsTheTaskAndTheWorkerConfig) {
  struct Case {
    protocol::LeaseResponse lease;
    int threads;
    const char *extension, *argv;
  };
  const Case cases[] = {
      {lease(7, 16, 0, 16), 0, ".exr",
       "/opt/vesper/bin/vesper render s.json -o out --spp 16 --sample-begin 0 --sample-end 16 "
       "--frame 7 --scene-dir-only"},
      {lease(3, 16, 4, 8), 2, ".vpartial",
       "/opt/vesper/bin/vesper render s.json -o out --spp 16 --sample-begin 4 --sample-end 8 "
       "--frame 3 --scene-dir-only --partial --threads 2"},
      {with_overrides(lease(4, 32, 0, 32)), 1, ".exr",
       "/opt/vesper/bin/vesper render s.json -o out --spp 32 --sample-begin 0 --sample-end 32 "
       "--frame 4 --scene-dir-only --aov variance,albedo --layer-variance --seed 11 --scale 0.125 "
       "--half --threads 1"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(render_output_extension(c.lease), c.extension);
    EXPECT_EQ(command_line(render_command(c.lease, config(c.threads), "s.json", "out")), c.argv);
  }
}

// The lease's budget (this task's share of its frame's) goes on as the
// render's flags, each number as the shortest text that reads back exactly.
TEST(RenderCommand, PassesTheTasksBudget) {
  protocol::LeaseResponse split = lease(2, 256, 64, 128);
  split.noise_target = 0.01 * std::sqrt(4.0);
  split.min_spp = 16;
  split.time_limit = 7.5;
  EXPECT_EQ(
      command_line(render_command(split, config(0), "s.json", "out")),
      "/opt/vesper/bin/vesper render s.json -o out --spp 256 --sample-begin 64 "
      "--sample-end 128 --frame 2 --scene-dir-only --partial --noise-target 0.02 --max-spp 256 "
      "--min-spp 16 --time-limit 7.5");
  protocol::LeaseResponse whole = lease(1, 64, 0, 64);
  whole.noise_target = 0.1 / std::sqrt(0.36);  // not a short decimal
  const auto argv = render_command(whole, config(0), "s.json", "out.exr");
  const auto at = std::find(argv.begin(), argv.end(), "--noise-target");
  ASSERT_NE(at, argv.end());
  EXPECT_EQ(std::stod(*(at + 1)), *whole.noise_target);  // exact round trip
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--min-spp"), 0);
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--time-limit"), 0);
  EXPECT_EQ(render_output_extension(whole), ".exr");
  EXPECT_EQ(describe_budget(split), ", noise target 0.02 (min spp 16), time limit 7.5 s");
  EXPECT_EQ(describe_budget(lease(1, 4, 0, 4)), "");
}

TEST(RenderCommand, LeavesTheSeedToTheSceneAndTheProgressLinesOn) {
  // Without a seed override the renderer takes the scene's render.seed; -q would silence the
  // progress lines the heartbeat reports.
  const auto argv = render_command(lease(1, 4, 0, 4), config(1), "s.json", "r.exr");
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--seed"), 0);
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "-q"), 0);
  EXPECT_EQ(command_line({"vesper", "render", "s.json"}), "vesper render s.json");
}

}  // namespace
}  // namespace vesper::worker_detail
