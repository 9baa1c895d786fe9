// The worker's child render command line: built from the task and the worker
// config only (the scene file is never parsed for it).
#include "worker/render_command.h"

#include <gtest/gtest.h>

#include <algorithm>

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

WorkerConfig config(int threads) {
  WorkerConfig c;
  c.vesper_binary = "/opt/vesper/bin/vesper";
  c.render_threads = threads;
  return c;
}

TEST(RenderCommand, WholeFrameRendersAnExrAtTheTasksFrame) {
  const protocol::LeaseResponse t = lease(7, 16, 0, 16);
  EXPECT_EQ(render_output_extension(t), ".exr");
  const std::vector<std::string> expected = {"/opt/vesper/bin/vesper",
                                             "render",
                                             "/c/jobs/k/scene.json",
                                             "-o",
                                             "/c/tmp/r.exr",
                                             "--spp",
                                             "16",
                                             "--sample-begin",
                                             "0",
                                             "--sample-end",
                                             "16",
                                             "--frame",
                                             "7"};
  EXPECT_EQ(render_command(t, config(0), "/c/jobs/k/scene.json", "/c/tmp/r.exr"), expected);
}

TEST(RenderCommand, SampleRangeRendersAPartialWithTheWorkersThreads) {
  const protocol::LeaseResponse t = lease(3, 16, 4, 8);
  EXPECT_EQ(render_output_extension(t), ".vpartial");
  const std::vector<std::string> expected = {"/opt/vesper/bin/vesper",
                                             "render",
                                             "s.json",
                                             "-o",
                                             "r.vpartial",
                                             "--spp",
                                             "16",
                                             "--sample-begin",
                                             "4",
                                             "--sample-end",
                                             "8",
                                             "--frame",
                                             "3",
                                             "--partial",
                                             "--threads",
                                             "2"};
  EXPECT_EQ(render_command(t, config(2), "s.json", "r.vpartial"), expected);
}

TEST(RenderCommand, LeavesTheSeedToTheSceneAndTheProgressLinesOn) {
  // The renderer takes the scene's render.seed itself; -q would silence the
  // progress lines the heartbeat reports.
  const auto argv = render_command(lease(1, 4, 0, 4), config(1), "s.json", "r.exr");
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "--seed"), 0);
  EXPECT_EQ(std::count(argv.begin(), argv.end(), "-q"), 0);
  EXPECT_EQ(command_line({"vesper", "render", "s.json"}), "vesper render s.json");
}

}  // namespace
}  // namespace vesper::worker_detail
