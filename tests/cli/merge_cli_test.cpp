// `vesper render --partial` and `vesper merge` as a user (or the farm) runs
// them: four partial renders of uneven sample ranges merge into an EXR that is
// bitwise identical to `vesper render` of the whole range.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "../common/cli_runner.h"
#include "renderer/output/exr_io.h"

namespace fs = std::filesystem;

namespace {

using vesper::test::RunResult;
using vesper::test::slurp;

class MergeCli : public vesper::test::CliTest {
 protected:
  // Subcommands differ per run: the runner's own subcommand is empty.
  MergeCli() : CliTest("") {}

  // The night room (fog, light groups, path layers, a variant layer) at 32x24.
  fs::path small_night_room() {
    const fs::path src = fs::path(VESPER_SOURCE_DIR) / "scenes/night-room/scene.json";
    std::string text = slurp(src);
    auto replace = [&](const std::string& from, const std::string& to) {
      const size_t at = text.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      if (at != std::string::npos) text.replace(at, from.size(), to);
    };
    replace("\"width\": 400, \"height\": 250", "\"width\": 32, \"height\": 24");
    const std::string cube = "\"../cornell/cube.obj\"";
    const std::string abs_cube =
        "\"" + (fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/cube.obj").string() + "\"";
    for (size_t at = text.find(cube); at != std::string::npos; at = text.find(cube))
      text.replace(at, cube.size(), abs_cube);
    const fs::path scene = dir_ / "night.json";
    std::ofstream(scene) << text;
    return scene;
  }

  std::string s(const fs::path& p) { return p.string(); }
};

const std::string kCommon = " --spp 11 --threads 2 --aov albedo,normal,depth,diffuse_direct -q";

TEST_F(MergeCli, FourPartialsMergeBitwiseToTheSingleRender) {
  const fs::path scene = small_night_room();
  const int cuts[] = {0, 2, 3, 8, 11};
  std::string parts;
  for (int i = 3; i >= 0; --i) {  // rendered and listed out of order
    const fs::path p = dir_ / ("p" + std::to_string(i) + ".vpartial");
    const RunResult r = run("render " + s(scene) + " -o " + s(p) + kCommon + " --frame 4" +
                            " --sample-begin " + std::to_string(cuts[i]) + " --sample-end " +
                            std::to_string(cuts[i + 1]) + " --partial");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, s(p) + "\n");
    parts += " " + s(p);
  }
  const fs::path merged = dir_ / "merged.exr", single = dir_ / "single.exr";
  const RunResult m = run("merge -o " + s(merged) + parts + " -q");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(m.out, s(merged) + "\n");
  EXPECT_EQ(m.err.find("not complete"), std::string::npos) << m.err;
  const RunResult r = run("render " + s(scene) + " -o " + s(single) + kCommon + " --frame 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const vesper::LayeredImage a = vesper::read_exr(merged), b = vesper::read_exr(single);
  EXPECT_EQ(a.channels, b.channels);
  for (const char* ch : {"albedo.R", "diffuse_direct.B", "fog.A", "candles.R", "rays_dense.G"})
    EXPECT_GE(a.channel_index(ch), 0) << ch;
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)));
  auto strip = [](std::map<std::string, std::string> meta) {
    meta.erase("vesper:render_seconds");
    return meta;
  };
  EXPECT_EQ(strip(a.metadata), strip(b.metadata));
  EXPECT_EQ(a.metadata.at("vesper:spp"), "11");
  EXPECT_EQ(a.metadata.at("vesper:frame"), "4");
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(MergeCli, MismatchesAndDamagedFilesFailNamingTheFile) {
  const fs::path scene = small_night_room();
  auto partial = [&](const std::string& name, int begin, int end, const std::string& extra = "") {
    const fs::path p = dir_ / name;
    const RunResult r =
        run("render " + s(scene) + " -o " + s(p) + " --spp 4 -q --partial" + " --sample-begin " +
            std::to_string(begin) + " --sample-end " + std::to_string(end) + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return p;
  };
  const fs::path a = partial("a.vpartial", 0, 2), b = partial("b.vpartial", 2, 4);
  const fs::path overlap = partial("overlap.vpartial", 1, 4);
  const fs::path seed = partial("seed.vpartial", 2, 4, " --seed 5");
  const fs::path out = dir_ / "out.exr";

  auto expect_fail = [&](const std::string& inputs, std::initializer_list<std::string> needles) {
    const RunResult r = run("merge -o " + s(out) + " " + inputs);
    EXPECT_NE(r.exit_code, 0) << inputs;
    EXPECT_EQ(r.out, "") << inputs;
    for (const std::string& n : needles)
      EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' not in: " << r.err;
    EXPECT_FALSE(fs::exists(out)) << inputs;
  };
  expect_fail(s(a) + " " + s(overlap), {s(a), s(overlap), "overlaps"});
  expect_fail(s(a) + " " + s(seed), {s(seed), "seed", s(a)});

  // Another scene (other hash).
  std::string other_text = slurp(scene);
  other_text.replace(other_text.find("\"max_depth\": 6"), 14, "\"max_depth\": 5");
  const fs::path other_scene = dir_ / "other.json";
  std::ofstream(other_scene) << other_text;
  const fs::path other = dir_ / "other.vpartial";
  ASSERT_EQ(
      run("render " + s(other_scene) + " -o " + s(other) + " --spp 4 --sample-begin 2 -q --partial")
          .exit_code,
      0);
  expect_fail(s(a) + " " + s(other), {s(other), "scene hash", s(a)});

  const std::string bytes = slurp(b);
  const fs::path truncated = dir_ / "truncated.vpartial";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  expect_fail(s(a) + " " + s(truncated), {s(truncated), "truncated"});
  const fs::path magic = dir_ / "magic.vpartial";
  std::ofstream(magic) << "not a partial\n";
  expect_fail(s(a) + " " + s(magic), {s(magic), "bad magic"});

  // An EXR is not a partial either; and the good pair still merges.
  const fs::path exr = dir_ / "full.exr";
  ASSERT_EQ(run("render " + s(scene) + " -o " + s(exr) + " --spp 4 -q").exit_code, 0);
  expect_fail(s(a) + " " + s(exr), {s(exr), "bad magic"});
  const RunResult ok = run("merge -o " + s(out) + " " + s(b) + " " + s(a) + " -q");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(vesper::read_exr(out).pixels, vesper::read_exr(exr).pixels);
}

TEST_F(MergeCli, AnIncompleteFrameMergesWithAWarning) {
  const fs::path scene = small_night_room();
  const fs::path p = dir_ / "p.vpartial", out = dir_ / "o.exr";
  ASSERT_EQ(
      run("render " + s(scene) + " -o " + s(p) + " --spp 4 --sample-end 3 --partial -q").exit_code,
      0);
  const RunResult r = run("merge -o " + s(out) + " " + s(p));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("not complete"), std::string::npos) << r.err;
  EXPECT_EQ(vesper::read_exr(out).metadata.at("vesper:sample_end"), "3");
}

}  // namespace
