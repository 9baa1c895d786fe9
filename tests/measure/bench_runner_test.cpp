// The runner with a fake renderer (Gaussian noise of a known size around a
// fixed picture): references rendered once and then read from the cache, a
// corrupt cache file rendered again, curves that fall with spp, a failing
// renderer recorded, a scene with an absent asset skipped, a peer compared.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "measure/bench_runner.h"
#include "synthetic_images.h"
#include "tests/common/temp_dir.h"

namespace vesper::measure {
namespace {

namespace fs = std::filesystem;

struct Calls {
  int references = 0, rungs = 0;
};

// Renders truth * (1 + N(0, 0.5^2 / spp)), deterministic in (seed, spp);
// its time is 1 ms per spp, scaled by `slowness`.
BenchRenderer fake(const std::string& name, Calls& calls, double slowness = 1, bool fail = false) {
  BenchRenderer r;
  r.name = name;
  r.cache_key = name + " 1.0";
  r.render = [&calls, slowness, fail](const BenchScene& s, int spp, uint64_t seed, int) {
    if (fail) throw std::runtime_error("fake: " + s.name + ": out of luck");
    (seed > 1000 ? calls.references : calls.rungs)++;
    std::mt19937_64 rng(seed * 7919 + uint64_t(spp));
    RenderedImage out;
    out.image = synth::noisy(synth::truth_image(s.width, s.height), 0.5 / std::sqrt(spp), rng);
    out.render_seconds = 1e-3 * spp * slowness;
    out.wall_seconds = out.render_seconds + 0.01;
    return out;
  };
  return r;
}

class BenchRunnerTest : public ::testing::Test {
 protected:
  BenchRunnerTest() {
    const fs::path cornell = fs::path(VESPER_SOURCE_DIR) / "scenes/cornell";
    fs::create_directories(dir_ / "box");
    fs::copy_file(cornell / "scene.json", dir_ / "box/scene.json");
    fs::copy_file(cornell / "cube.obj", dir_ / "box/cube.obj");
    fs::create_directories(dir_ / "nocube");
    fs::copy_file(cornell / "scene.json", dir_ / "nocube/scene.json");  // cube.obj absent
    set_ = parse_bench_set_text(
        R"({"format": "vesper-bench/1", "scenes": [
          {"name": "box", "path": "box/scene.json", "kind": "surface", "width": 32,
           "height": 32, "spp": [1, 4, 16, 64], "reference_spp": 2048},
          {"name": "nocube", "path": "nocube/scene.json", "kind": "volume", "width": 32,
           "height": 32, "spp": [1], "reference_spp": 2}]})",
        dir_ / "set.json");
    options_.refs_dir = dir_ / "refs";
  }
  test::TempDir temp_{"measure"};
  fs::path dir_ = temp_.path();
  BenchSet set_;
  RunnerOptions options_;
};

TEST_F(BenchRunnerTest, RendersTheReferenceOnceThenReadsItFromTheCache) {
  Calls calls;
  const BenchReport first = run_bench(set_, {fake("vesper", calls)}, options_);
  EXPECT_EQ(calls.references, 2);  // two halves
  EXPECT_EQ(calls.rungs, 4);
  const RendererRun& run = first.scenes[0].runs.at(0);
  EXPECT_FALSE(run.reference_cached);
  EXPECT_TRUE(fs::exists(run.reference_file));
  // Each rung's expected relMSE is about 0.25 / spp (+ the floor, ~0.25 / 2048 / 2).
  ASSERT_EQ(run.curve.size(), 4u);
  for (size_t i = 1; i < run.curve.size(); ++i)
    EXPECT_LT(run.curve[i].relmse, run.curve[i - 1].relmse);
  EXPECT_GT(run.noise_floor, 0);
  EXPECT_LT(run.noise_floor, run.curve.back().relmse / 10);
  EXPECT_EQ(run.times.at(0).time.estimate, TimeEstimate::Interpolated);  // 1e-2 at ~25 spp

  const BenchReport second = run_bench(set_, {fake("vesper", calls)}, options_);
  EXPECT_EQ(calls.references, 2);  // not rendered again
  EXPECT_TRUE(second.scenes[0].runs[0].reference_cached);
  EXPECT_DOUBLE_EQ(second.scenes[0].runs[0].noise_floor, run.noise_floor);
  EXPECT_DOUBLE_EQ(second.scenes[0].runs[0].curve[3].relmse, run.curve[3].relmse);
}

TEST_F(BenchRunnerTest, ACorruptCacheFileIsRenderedAgainWithAWarning) {
  Calls calls;
  const BenchReport first = run_bench(set_, {fake("vesper", calls)}, options_);
  std::ofstream(first.scenes[0].runs[0].reference_file, std::ios::trunc) << "not an EXR";
  std::vector<std::string> warnings;
  RunnerEvents ev;
  ev.warn = [&](const std::string& m) { warnings.push_back(m); };
  const BenchReport second = run_bench(set_, {fake("vesper", calls)}, options_, ev);
  EXPECT_EQ(calls.references, 4);
  EXPECT_FALSE(second.scenes[0].runs[0].reference_cached);
  ASSERT_GE(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("unusable"), std::string::npos) << warnings[0];
  // The next run reads the fresh file.
  EXPECT_TRUE(
      run_bench(set_, {fake("vesper", calls)}, options_).scenes[0].runs[0].reference_cached);
}

TEST_F(BenchRunnerTest, AnotherCacheKeyOrSizeIsAnotherReference) {
  Calls calls;
  run_bench(set_, {fake("vesper", calls)}, options_);
  BenchRenderer newer = fake("vesper", calls);
  newer.cache_key = "vesper 1.1";
  EXPECT_FALSE(run_bench(set_, {newer}, options_).scenes[0].runs[0].reference_cached);
  options_.quick = true;  // 32x24
  EXPECT_FALSE(run_bench(set_, {newer}, options_).scenes[0].runs[0].reference_cached);
  EXPECT_EQ(calls.references, 6);
}

TEST_F(BenchRunnerTest, AbsentAssetSkipsTheSceneWithANote) {
  Calls calls;
  const BenchReport r = run_bench(set_, {fake("vesper", calls)}, options_);
  const SceneResult& s = r.scenes.at(1);
  EXPECT_TRUE(s.skipped);
  EXPECT_NE(s.note.find("cube.obj"), std::string::npos) << s.note;
  EXPECT_TRUE(s.runs.empty());
}

TEST_F(BenchRunnerTest, AFailingRendererIsRecordedAndTheRunGoesOn) {
  Calls calls;
  const BenchReport r =
      run_bench(set_, {fake("vesper", calls), fake("peer", calls, 1, true)}, options_);
  ASSERT_EQ(r.scenes[0].runs.size(), 2u);
  EXPECT_TRUE(r.scenes[0].runs[0].error.empty());
  EXPECT_NE(r.scenes[0].runs[1].error.find("out of luck"), std::string::npos);
  EXPECT_TRUE(r.any_error());
  ASSERT_EQ(r.scenes[0].comparisons.size(), 1u);
  EXPECT_FALSE(r.scenes[0].comparisons[0].agreement.has_value());
  EXPECT_FALSE(r.scenes[0].comparisons[0].ratios.at(0).ratio.has_value());
}

TEST_F(BenchRunnerTest, APeerTwiceAsSlowGivesRatioOneHalf) {
  Calls calls;
  // Same noise at twice the time: equal-error ratio exactly 0.5 (same images, same curve shape).
  const BenchReport r =
      run_bench(set_, {fake("vesper", calls), fake("peer", calls, 2.0)}, options_);
  const PeerComparison& c = r.scenes[0].comparisons.at(0);
  ASSERT_TRUE(c.ratios.at(0).ratio.has_value());
  EXPECT_NEAR(*c.ratios[0].ratio, 0.5, 1e-9);
  EXPECT_FALSE(c.ratios[0].approximate);
  EXPECT_EQ(c.ratios[0].goal, 0.8);
  EXPECT_TRUE(*c.ratios[0].goal_met);
  ASSERT_TRUE(c.agreement.has_value());
  EXPECT_FALSE(c.agreement->flagged);
  EXPECT_NEAR(c.agreement->mean_ratio, 1.0, 1e-9);  // both references are the same images
}

}  // namespace
}  // namespace vesper::measure
