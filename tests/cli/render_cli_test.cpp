// `vesper render` as a user runs it: real process, real files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../common/cli_runner.h"
#include "renderer/output/exr_io.h"

namespace fs = std::filesystem;

namespace {

using vesper::test::RunResult;
using vesper::test::slurp;

class RenderCli : public vesper::test::CliTest {
 protected:
  RenderCli() : CliTest("render") {}
};

const std::string kCornell = std::string(VESPER_SOURCE_DIR) + "/scenes/cornell/scene.json";

TEST_F(RenderCli, RendersTheCornellBoxWithAovsAndMetadata) {
  const fs::path exr = dir_ / "cornell.exr";
  const RunResult r = run(kCornell + " -o " + exr.string() +
                          " --spp 2 --seed 9 --threads 2 --aov albedo,normal,depth -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, exr.string() + "\n");
  const vesper::LayeredImage img = vesper::read_exr(exr);
  EXPECT_EQ(img.width, 256);
  EXPECT_EQ(img.height, 256);
  for (const char* ch : {"R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B", "normal.X",
                         "normal.Y", "normal.Z", "depth.Z"})
    EXPECT_GE(img.channel_index(ch), 0) << "missing channel " << ch;
  EXPECT_EQ(img.channel_count(), 11u);
  EXPECT_EQ(img.metadata.at("vesper:spp"), "2");
  EXPECT_EQ(img.metadata.at("vesper:seed"), "9");
  EXPECT_EQ(img.metadata.at("vesper:nonfinite_samples"), "0");
  EXPECT_FALSE(img.metadata.at("vesper:scene_hash").empty());
  for (float v : img.pixels) ASSERT_TRUE(std::isfinite(v));
  // No temporary file is left next to the output.
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(RenderCli, OiiotoolPullsALayerOutByName) {
  const fs::path exr = dir_ / "c.exr", albedo = dir_ / "albedo.exr";
  ASSERT_EQ(run(kCornell + " -o " + exr.string() + " --spp 1 --aov albedo -q").exit_code, 0);
  const std::string cmd = "oiiotool " + exr.string() +
                          " --ch albedo.R,albedo.G,albedo.B --chnames R,G,B -o " + albedo.string() +
                          " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const vesper::LayeredImage img = vesper::read_exr(albedo);
  EXPECT_EQ(img.channel_count(), 3u);
}

TEST_F(RenderCli, RejectsABadSceneNamingFileAndPathAndWritesNothing) {
  const fs::path scene = dir_ / "bad.json", exr = dir_ / "bad.exr";
  std::string text = slurp(kCornell);
  const std::string from = "\"radiance\": [17, 12, 4]";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "\"radiance\": [17, -12, 4]");
  std::ofstream(scene) << text;
  fs::copy_file(fs::path(kCornell).parent_path() / "cube.obj", dir_ / "cube.obj");
  const RunResult r = run(scene.string() + " -o " + exr.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(scene.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/lights/0/radiance"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(exr));
}

TEST_F(RenderCli, RejectsAnUnknownAovAndAMissingOutputDirectory) {
  EXPECT_EQ(run(kCornell + " -o " + (dir_ / "x.exr").string() + " --aov albedo,speculr").exit_code,
            2);
  const RunResult r = run(kCornell + " -o " + (dir_ / "no/such/dir/x.exr").string() + " --spp 1");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("no/such/dir"), std::string::npos) << r.err;
}

TEST_F(RenderCli, ClampIsRecordedInTheHeaderAndANonPositiveOneIsRefused) {
  const fs::path exr = dir_ / "clamped.exr";
  const RunResult r = run(kCornell + " -o " + exr.string() + " --spp 1 --clamp 2.5 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(vesper::read_exr(exr).metadata.at("vesper:clamp"), "2.5");
  const RunResult bad = run(kCornell + " -o " + (dir_ / "x.exr").string() + " --clamp 0");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--clamp"), std::string::npos) << bad.err;
}

TEST_F(RenderCli, PhotonMergingIsRecordedInTheHeaderAndANonPositiveRadiusIsRefused) {
  const std::string fog = std::string(VESPER_SOURCE_DIR) + "/scenes/fog-shafts/scene.json ";
  const fs::path exr = dir_ / "photons.exr";
  const RunResult r = run(fog + "-o " + exr.string() +
                          " --spp 1 --scale 0.1 --photon-merging --photon-radius 0.2 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string recorded = vesper::read_exr(exr).metadata.at("vesper:photon_merging");
  EXPECT_EQ(recorded.rfind("radius 0.2 photons ", 0), 0u) << recorded;
  const RunResult bad = run(fog + "-o " + (dir_ / "x.exr").string() + " --photon-radius -1");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--photon-radius"), std::string::npos) << bad.err;
}

TEST_F(RenderCli, MissingSceneFileIsAClearError) {
  const RunResult r = run((dir_ / "nope.json").string() + " -o " + (dir_ / "x.exr").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("nope.json"), std::string::npos) << r.err;
}

TEST_F(RenderCli, SampleRangesFromTheCommandLineMergeToTheFullRender) {
  const fs::path a = dir_ / "a.exr", b = dir_ / "b.exr", full = dir_ / "full.exr";
  ASSERT_EQ(run(kCornell + " -o " + a.string() + " --spp 4 --sample-end 1 -q").exit_code, 0);
  ASSERT_EQ(run(kCornell + " -o " + b.string() + " --spp 4 --sample-begin 1 -q").exit_code, 0);
  ASSERT_EQ(run(kCornell + " -o " + full.string() + " --spp 4 -q").exit_code, 0);
  const auto ia = vesper::read_exr(a), ib = vesper::read_exr(b), ifull = vesper::read_exr(full);
  ASSERT_EQ(ia.pixels.size(), ifull.pixels.size());
  double max_rel = 0;
  for (size_t i = 0; i < ifull.pixels.size(); ++i) {
    const double merged = (1.0 * ia.pixels[i] + 3.0 * ib.pixels[i]) / 4.0;
    max_rel = std::max(max_rel, std::abs(merged - ifull.pixels[i]) /
                                    std::max(1e-3, double(std::abs(ifull.pixels[i]))));
  }
  EXPECT_LT(max_rel, 1e-6);
}

// --half as oiiotool sees it: half colour, float32 data channels, typed
// metadata; partials rendered with it merge into the same half file.
TEST_F(RenderCli, HalfWritesHalfColourChannelsAndTypedMetadata) {
  const fs::path exr = dir_ / "half.exr", info = dir_ / "info.txt";
  const std::string flags = " --spp 2 --seed 9 --aov albedo,depth --half -q";
  ASSERT_EQ(run(kCornell + " -o " + exr.string() + flags).exit_code, 0);
  const std::string cmd = "oiiotool --info -v " + exr.string() + " > " + info.string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string text = slurp(info);
  for (const char* want : {"R (half)", "albedo.B (half)", "depth.Z (float)", "vesper:spp: 2\n",
                           "vesper:seed: \"9\"", "vesper:pixel_type: \"half\"", "worldToNDC: "})
    EXPECT_NE(text.find(want), std::string::npos) << want << " in\n" << text;

  const fs::path a = dir_ / "a.vpartial", b = dir_ / "b.vpartial", merged = dir_ / "m.exr";
  ASSERT_EQ(run(kCornell + " -o " + a.string() + flags + " --sample-end 1 --partial").exit_code, 0);
  ASSERT_EQ(run(kCornell + " -o " + b.string() + flags + " --sample-begin 1 --partial").exit_code,
            0);
  const std::string merge = std::string(VESPER_BINARY) + " merge -q -o " + merged.string() + " " +
                            a.string() + " " + b.string();
  ASSERT_EQ(std::system(merge.c_str()), 0);
  // Equal to the half render's values: the merged frame is half-encoded too.
  EXPECT_EQ(vesper::read_exr(merged).pixels, vesper::read_exr(exr).pixels);
}

}  // namespace

namespace {

TEST_F(RenderCli, NightRoomLayersArePulledOutByNameWithOiiotool) {
  const fs::path exr = dir_ / "night.exr";
  const std::string scene = std::string(VESPER_SOURCE_DIR) + "/scenes/night-room/scene.json";
  const RunResult r = run(scene + " -o " + exr.string() + " --spp 1 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const vesper::LayeredImage img = vesper::read_exr(exr);
  for (const char* layer : {"fog", "surfaces", "lightrays", "candles", "rays_dense"}) {
    for (const char* c : {".R", ".G", ".B"})
      EXPECT_GE(img.channel_index(std::string(layer) + c), 0) << layer << c;
    const fs::path out = dir_ / (std::string(layer) + ".exr");
    const std::string cmd = "oiiotool " + exr.string() + " --ch " + layer + ".R," + layer + ".G," +
                            layer + ".B --chnames R,G,B -o " + out.string() + " >/dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << layer;
    EXPECT_TRUE(fs::exists(out)) << layer;
  }
  EXPECT_GE(img.channel_index("fog.A"), 0);          // volume layers carry alpha
  EXPECT_LT(img.channel_index("surfaces.A"), 0);     // surface layers do not
  EXPECT_EQ(img.metadata.at("vesper:passes"), "2");  // beauty pass + the rays_dense variant
}

}  // namespace
