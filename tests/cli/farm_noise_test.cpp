// Noise targets and time limits on the farm, end to end: `vesper submit
// --noise-target` on real server and worker processes, a whole frame and the
// same frame split into four tasks (each aiming at X * sqrt(4)), the noise
// each merged frame reached as `vesper status` prints it; a time limit shared
// by a split frame's tasks; bad budgets as usage errors naming the flag.
#include <fmt/format.h>

#include "renderer/output/metadata_keys.h"
#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

// A job's first frame is ready (a split frame after its merge).
// Ready, and its metadata read (spp_mean is in every budgeted output): the
// server reads an output's noise after recording it, so "ready" alone races it.
bool first_frame_ready(const nlohmann::json& job) {
  if (!job.contains("frames")) return false;
  const nlohmann::json& f = job.at("frames").at(0);
  return f.at("state") == "ready" && f.contains("spp_mean");
}

}  // namespace

// The frame: 24x24 Cornell box, max 1024 spp, noise target X = 0.05. The bound
// on the noise reached is X for both jobs:
//  - a pixel stops sampling only when its estimated relative error of the
//    mean (and its 3x3 neighbourhood's RMS) is at most its task's target;
//    the whole frame's pixels are at most X unless they reach the 1024 cap
//    (a few: ~4x the mean spp);
//  - each of the four tasks of the split frame stops at 2X = X * sqrt(4) and
//    takes about a quarter of the samples; the merged mean averages four
//    independent estimates, so its variance is a quarter of each one's:
//    about X again, and noise_reached, an RMS over 576 pixels, averages the
//    estimates' own noise out.
// Both are deterministic for the scene's seed. Tasks aiming at X each (no
// sqrt(J)) would take ~2x the samples (the spp check below fails); at X * J
// the merged noise is ~X * sqrt(J) (the bound fails). X is small enough that
// the whole frame needs well over the four tasks' 4 x min_spp.
TEST_F(FarmTest, ANoiseTargetIsMetWholeAndSplitAndStatusShowsIt) {
  const double x = 0.05;
  const auto config = write_config(10);
  const auto scene = write_scene(24, 24, 16);
  start_server(config);
  start_worker("w1", config);
  start_worker("w2", config);
  const std::string budget = fmt::format("--noise-target {} --max-spp 1024", x);
  const long long whole = submit(scene.string() + " --name whole " + budget);
  const long long split = submit(scene.string() + " --name split --split 256 " + budget);
  const nlohmann::json a = wait_job(whole, 180, first_frame_ready).at("frames").at(0);
  const nlohmann::json b = wait_job(split, 180, first_frame_ready).at("frames").at(0);
  ASSERT_EQ(job(split).at("total"), 4);
  for (const nlohmann::json& f : {a, b}) {
    ASSERT_TRUE(f.contains("noise_reached") && f.contains("spp_mean")) << f.dump();
    EXPECT_LE(f.at("noise_reached").get<double>(), x) << f.dump();
    EXPECT_GT(f.at("noise_reached").get<double>(), x / 4) << f.dump();  // not oversampled
    const std::string stop = f.at("stop_reason");  // a merged frame lists its tasks' reasons
    EXPECT_TRUE(stop == "noise_target" || stop == "max_spp" || stop == "max_spp,noise_target")
        << f.dump();
  }
  // The split frame took about the whole frame's samples: X * sqrt(4) per task.
  const double ratio = b.at("spp_mean").get<double>() / a.at("spp_mean").get<double>();
  EXPECT_GT(ratio, 2.0 / 3) << a.dump() << b.dump();
  EXPECT_LT(ratio, 1.5) << a.dump() << b.dump();
  // Each task was told its share.
  EXPECT_NE((worker_log("w1") + worker_log("w2")).find("noise target 0.1 (min spp 16)"),
            std::string::npos)
      << worker_log("w1");

  // `vesper status` prints it, as does the fetched frame's own metadata.
  const RunResult st = farm(fmt::format("status {}", split));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  EXPECT_NE(st.out.find("noise reached"), std::string::npos) << st.out;
  EXPECT_NE(st.out.find(fmt::format("{:.4g}", b.at("noise_reached").get<double>())),
            std::string::npos)
      << st.out;
  EXPECT_NE(st.out.find(fmt::format("{:.1f}", b.at("spp_mean").get<double>())), std::string::npos)
      << st.out;
  const RunResult f = farm(fmt::format("fetch {} -o {}", split, (dir_ / "frames").string()));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const LayeredImage merged = read_exr(dir_ / "frames/split.0001.exr");
  EXPECT_DOUBLE_EQ(std::stod(merged.metadata.at(metadata_key::kNoiseReached)),
                   b.at("noise_reached").get<double>());
}

// A time limit is per frame: a frame split into four tasks gives each a
// quarter of it, so the frame costs the same render time however it is split.
TEST_F(FarmTest, ATimeLimitIsSharedByASplitFramesTasks) {
  const auto config = write_config(10);
  const auto scene = write_scene(24, 24, 16);
  start_server(config);
  start_worker("w1", config);
  const long long id =
      submit(scene.string() + " --spp 1048576 --split 262144 --time-limit 2 --name timed");
  const nlohmann::json frame = wait_job(id, 180, first_frame_ready).at("frames").at(0);
  EXPECT_EQ(frame.at("stop_reason"), "time_limit") << frame.dump();
  ASSERT_TRUE(frame.contains("spp_mean")) << frame.dump();
  EXPECT_GT(frame.at("spp_mean").get<double>(), 0);
  EXPECT_LT(frame.at("spp_mean").get<double>(), 1048576);
  EXPECT_NE(worker_log("w1").find("time limit 0.5 s"), std::string::npos) << worker_log("w1");
  const RunResult st = farm(fmt::format("status {}", id));
  EXPECT_NE(st.out.find("time_limit"), std::string::npos) << st.out;
}

// Checked before anything is uploaded (no server here): exit 2, naming the
// flag (or the job file's key, with its JSON path).
TEST_F(FarmTest, BadBudgetsAreUsageErrorsNamingTheFlag) {
  const auto scene = write_scene(8, 8, 16);
  const std::string submit = "submit " + scene.string() + " --server http://127.0.0.1:9 --token t ";
  struct Case {
    std::string args, expected;
  };
  const Case cases[] = {
      {"--noise-target 0", "--noise-target"},
      {"--noise-target -0.1", "--noise-target"},
      {"--time-limit 0", "--time-limit"},
      {"--min-spp 0 --noise-target 0.1", "--min-spp"},
      {"--min-spp 8", "--min-spp"},   // needs a noise target
      {"--max-spp 64", "--max-spp"},  // needs a noise target
      {"--noise-target 0.1 --min-spp 64 --max-spp 32", "--min-spp"},
      {"--noise-target 0.1 --min-spp 17", "--min-spp"},  // more than the scene's spp
      {"--noise-target inf", "--noise-target"},
  };
  for (const Case& c : cases) {
    const RunResult r = run(submit + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << ": " << r.err;
  }
  const auto job_file = dir_ / "job.json";
  std::ofstream(job_file) << R"({"format": "vesper-job/1", "scene": "scene/scene.json",
                                 "noise_target": 0})";
  const RunResult bad_key = run("submit " + job_file.string() + " --token t");
  EXPECT_EQ(bad_key.exit_code, 2) << bad_key.err;
  EXPECT_NE(bad_key.err.find("job.json: /noise_target: expected a positive number"),
            std::string::npos)
      << bad_key.err;
  std::ofstream(job_file) << R"({"format": "vesper-job/1", "scene": "scene/scene.json",
                                 "min_spp": 4})";
  const RunResult no_target = run("submit " + job_file.string() + " --token t");
  EXPECT_EQ(no_target.exit_code, 2) << no_target.err;
  EXPECT_NE(no_target.err.find("min_spp needs a noise_target"), std::string::npos) << no_target.err;
  const RunResult up =
      run("up --scene " + scene.string() + " --min-spp 8 --data-dir " + (dir_ / "farm").string());
  EXPECT_EQ(up.exit_code, 2) << up.err;
  EXPECT_NE(up.err.find("--min-spp"), std::string::npos) << up.err;
}

}  // namespace vesper::test
