// Noise targets and time limits through the server: the submit keys are
// validated naming their JSON path, each lease carries its task's share of
// the frame's budget, and each frame's noise is read from its output's EXR
// header (a one-task frame's result, a merged frame) into the job and frame
// listings.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "renderer/output/exr_io.h"
#include "server/frame_noise.h"
#include "tests/server/server_fixture.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

// A 2x2 EXR whose header carries `metadata`, as bytes.
std::string exr_bytes(const fs::path& dir, const std::map<std::string, std::string>& metadata) {
  fs::create_directories(dir);
  const fs::path file = dir / "frame.exr";
  OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::FLOAT);
  for (const auto& [key, value] : metadata) spec.attribute(key, value);
  auto out = OIIO::ImageOutput::create("openexr");
  EXPECT_TRUE(out && out->open(file.string(), spec));
  const float pixels[12] = {};
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels));
  out->close();
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

const std::map<std::string, std::string> kAdaptiveMetadata = {
    {"vesper:noise_target", "0.02"},
    {"vesper:noise_reached", "0.0187"},
    {"vesper:spp_mean", "41.25"},
    {"vesper:stop_reason", "noise_target"}};

class BudgetTest : public ServerTest {
 protected:
  json job_body(json budget, int spp = 64) {
    json body{
        {"scene", put_blob("{\"format\": \"vesper-scene/1\"}")}, {"frames", "1"}, {"spp", spp}};
    body.update(budget);
    return body;
  }
  // The 400 answer's `path` for a submit with these budget keys.
  std::string error_path(const json& budget, int spp = 64) {
    auto r = post("/jobs", job_body(budget, spp), sub());
    if (!r) return "no answer";
    if (r->status != 400) return "status " + std::to_string(r->status) + ": " + r->body;
    return json::parse(r->body).value("path", "");
  }
  // Completes every queued task of the job, task k (in lease order) with results[k].
  void complete_with(const std::vector<std::string>& results) {
    const std::string w = register_worker("w");
    for (const std::string& bytes : results) {
      const json l = lease(w);
      post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", put_blob(bytes)}}, wrk());
    }
  }
};

TEST_F(BudgetTest, BadBudgetsAre400NamingTheKey) {
  start();
  EXPECT_EQ(error_path({{"noise_target", 0}}), "/noise_target");
  EXPECT_EQ(error_path({{"noise_target", -0.1}}), "/noise_target");
  EXPECT_EQ(error_path({{"noise_target", "1%"}}), "/noise_target");
  EXPECT_EQ(error_path({{"time_limit", 0}}), "/time_limit");
  EXPECT_EQ(error_path({{"time_limit", -5}}), "/time_limit");
  EXPECT_EQ(error_path({{"min_spp", 0}, {"noise_target", 0.1}}), "/min_spp");
  EXPECT_EQ(error_path({{"max_spp", 0}, {"noise_target", 0.1}}), "/max_spp");
  EXPECT_EQ(error_path({{"min_spp", 65}, {"noise_target", 0.1}}), "/min_spp");  // > spp
  EXPECT_EQ(error_path({{"min_spp", 33}, {"max_spp", 32}, {"noise_target", 0.1}}), "/min_spp");
  EXPECT_EQ(error_path({{"min_spp", 4}}), "/min_spp");  // needs a noise target
  EXPECT_EQ(error_path({{"max_spp", 128}}), "/max_spp");
  EXPECT_EQ(error_path({{"noise_tagret", 0.1}}), "/noise_tagret");  // a typo is unknown
  auto r = post("/jobs", job_body({{"min_spp", 65}, {"noise_target", 0.1}}), sub());
  EXPECT_NE(r->body.find("[1, 64]"), std::string::npos) << r->body;
  EXPECT_TRUE(get_ok("/jobs").at("jobs").empty());
}

TEST_F(BudgetTest, EachLeaseCarriesItsTasksShareOfTheFrameBudget) {
  start();
  // max_spp replaces spp: frames of 128 samples in 4 tasks of 32.
  const json body =
      job_body({{"noise_target", 0.01}, {"min_spp", 8}, {"max_spp", 128}, {"time_limit", 20}}, 16);
  auto dry = post("/jobs?dry_run=1", body, sub());
  EXPECT_EQ(json::parse(dry->body).at("task_count"), 1);
  json split = body;
  split["samples_per_task"] = 32;
  EXPECT_EQ(post_ok("/jobs", split, sub(), 201).at("task_count"), 4);
  const std::string w = register_worker("w");
  for (int i = 0; i < 4; ++i) {
    const json l = lease(w);
    EXPECT_EQ(l.at("spp"), 128);
    EXPECT_EQ(l.at("task").at("sample_begin"), 32 * i);
    EXPECT_NEAR(l.at("noise_target").get<double>(), 0.02, 1e-15);  // 0.01 * sqrt(4)
    EXPECT_EQ(l.at("min_spp"), 8);
    EXPECT_NEAR(l.at("time_limit").get<double>(), 5.0, 1e-12);  // 20 s shared by 4
  }
  // A job without a budget leases without one.
  post_ok("/jobs", job_body(json::object()), sub(), 201);
  const json plain = lease(w);
  EXPECT_FALSE(plain.contains("noise_target") || plain.contains("min_spp") ||
               plain.contains("time_limit"))
      << plain.dump();
}

TEST_F(BudgetTest, AOneTaskFramesNoiseComesFromItsResultsHeader) {
  start();
  post_ok("/jobs", job_body({{"noise_target", 0.02}}), sub(), 201);
  post_ok("/jobs", job_body(json::object(), 8), sub(), 201);
  complete_with({exr_bytes(dir_ / "a", kAdaptiveMetadata), "not an image"});
  // Recorded before /complete answered: no waiting.
  const json adaptive = get_ok("/jobs/1").at("frames").at(0);
  EXPECT_EQ(adaptive.at("state"), "ready");
  EXPECT_EQ(adaptive.at("noise_reached"), 0.0187);
  EXPECT_EQ(adaptive.at("spp_mean"), 41.25);
  EXPECT_EQ(adaptive.at("stop_reason"), "noise_target");
  EXPECT_EQ(get_ok("/jobs/1/frames").at("frames").at(0), adaptive);
  // An output that does not say (here not even an EXR): no noise keys.
  const json plain = get_ok("/jobs/2").at("frames").at(0);
  EXPECT_EQ(plain.at("state"), "ready");
  EXPECT_FALSE(plain.contains("noise_reached") || plain.contains("spp_mean") ||
               plain.contains("stop_reason"))
      << plain.dump();
}

// A stand-in for `vesper merge -o OUT IN... -q` that writes `exr` as the merged frame.
fs::path merger_writing(const fs::path& dir, const fs::path& exr) {
  fs::create_directories(dir);
  const fs::path script = dir / "vesper";
  std::ofstream(script) << "#!/bin/sh\n[ \"$1\" = merge ] && [ \"$2\" = -o ] || exit 9\ncp '"
                        << exr.string() << "' \"$3\"\n";
  fs::permissions(script, fs::perms::owner_all);
  return script;
}

TEST_F(BudgetTest, AMergedFramesNoiseComesFromTheMergedHeader) {
  const std::string merged = exr_bytes(dir_ / "merged", kAdaptiveMetadata);
  ServerConfig c = config();
  c.vesper_binary = merger_writing(dir_ / "bin", dir_ / "merged" / "frame.exr");
  start(c);
  json body = job_body({{"noise_target", 0.02}});
  body["samples_per_task"] = 32;
  post_ok("/jobs", body, sub(), 201);
  complete_with({"partial 1", "partial 2"});
  json frame;
  // The merge runs in the background; a loaded CI machine (the full suite on
  // 2 cores) once took more than 5 s to spawn it, so wait up to 60 s.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    frame = get_ok("/jobs/1").at("frames").at(0);
    if (frame.at("state") == "ready") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  ASSERT_EQ(frame.at("state"), "ready") << frame.dump();
  EXPECT_EQ(frame.at("blob"), sha256_hex(merged));
  EXPECT_EQ(frame.at("noise_reached"), 0.0187);
  EXPECT_EQ(frame.at("spp_mean"), 41.25);
  // A restart keeps it (recorded in the store, not read again).
  start(c);
  EXPECT_EQ(get_ok("/jobs/1").at("frames").at(0), frame);
}

TEST(FrameNoise, ReadsTheHeaderAndNothingElse) {
  const test::TempDir dir("server");
  exr_bytes(dir.path(), {{"vesper:noise_reached", "0.5"}, {"vesper:stop_reason", "time_limit"}});
  const FrameNoise n = read_frame_noise(dir / "frame.exr");
  EXPECT_EQ(n.noise_reached, 0.5);
  EXPECT_FALSE(n.spp_mean);
  EXPECT_EQ(n.stop_reason, "time_limit");
  std::ofstream(dir / "junk") << "not an image";
  EXPECT_EQ(read_frame_noise(dir / "junk"), FrameNoise{});
  EXPECT_EQ(read_frame_noise(dir / "missing"), FrameNoise{});
}

// vesper writes the figures as double attributes: read to the last digit.
TEST(FrameNoise, ReadsTypedAttributesExactly) {
  const test::TempDir dir("server");
  LayeredImage img;
  img.width = img.height = 1;
  img.channels = {"R", "G", "B"};
  img.pixels = {0, 0, 0};
  img.metadata = {{"vesper:noise_reached", "0.018712345678901234"},
                  {"vesper:spp_mean", "41.25"},
                  {"vesper:stop_reason", "noise_target"}};
  write_exr(img, dir / "frame.exr");
  const FrameNoise n = read_frame_noise(dir / "frame.exr");
  EXPECT_EQ(n.noise_reached, 0.018712345678901234);
  EXPECT_EQ(n.spp_mean, 41.25);
  EXPECT_EQ(n.stop_reason, "noise_target");
}

}  // namespace
}  // namespace vesper
