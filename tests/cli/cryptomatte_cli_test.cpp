// `vesper render --aov cryptomatte` end to end: the EXR gets the Crypto
// layers, partial renders (local, or on a farm splitting the frame into
// tasks) merge to the same layers bit for bit, and `vesper comp` reads such a
// file like any other: the same composite as from the file without them, and
// only the graded beauty in its EXR.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstring>
#include <fstream>

#include "renderer/output/exr_io.h"
#include "tests/cli/farm_test_fixture.h"
#include "tests/common/crypto_header.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;

// Both files have the two types' name, hash, conversion and manifest attributes, equal.
void expect_same_crypto_header(const fs::path& a, const fs::path& b) {
  const auto header = crypto_header(b);
  EXPECT_EQ(manifest_count(header), 2);
  EXPECT_EQ(crypto_header(a), header);
}

class CryptomatteCli : public CliTest {
 protected:
  CryptomatteCli() : CliTest("") {}
  std::string scene() const {
    return std::string(VESPER_SOURCE_DIR) + "/scenes/cornell/scene.json";
  }
  std::string q(const fs::path& p) const { return "'" + p.string() + "'"; }
  RunResult render(const std::string& out, const std::string& flags) {
    return run("render " + q(scene()) + " --scale 0.125 --spp 4 -q -o " + q(dir_ / out) + " " +
               flags);
  }
};

TEST_F(CryptomatteCli, RenderWritesLayersAndCompLeavesThemAlone) {
  ASSERT_EQ(render("plain.exr", "").exit_code, 0);
  const RunResult r = render("crypto.exr", "--aov cryptomatte");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const LayeredImage img = read_exr(dir_ / "crypto.exr");
  for (const char* c : {"CryptoObject00.R", "CryptoObject02.A", "CryptoMaterial01.G"})
    EXPECT_GE(img.channel_index(c), 0) << c;

  for (const char* name : {"plain", "crypto"}) {
    const std::string in = std::string(name) + ".exr";
    const RunResult c =
        run("comp " + q(dir_ / in) + " -o " + q(dir_ / (std::string(name) + ".png")) + " --exr " +
            q(dir_ / (std::string(name) + ".comp.exr")));
    ASSERT_EQ(c.exit_code, 0) << name << ": " << c.err;
  }
  EXPECT_EQ(slurp(dir_ / "plain.png"), slurp(dir_ / "crypto.png"));
  const LayeredImage comp = read_exr(dir_ / "crypto.comp.exr");
  EXPECT_EQ(comp.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(comp.pixels, read_exr(dir_ / "plain.comp.exr").pixels);
}

// Two partial renders merge to the single render's Crypto layers, bit for bit.
TEST_F(CryptomatteCli, PartialRendersMergeToTheSingleRender) {
  ASSERT_EQ(render("single.exr", "--aov cryptomatte").exit_code, 0);
  ASSERT_EQ(render("a.vpartial", "--aov cryptomatte --partial --sample-end 1").exit_code, 0);
  const RunResult r = render("b.vpartial", "--aov cryptomatte --partial --sample-begin 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunResult m = run("merge -q -o " + q(dir_ / "merged.exr") + " " + q(dir_ / "b.vpartial") +
                          " " + q(dir_ / "a.vpartial"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const LayeredImage a = read_exr(dir_ / "merged.exr"), b = read_exr(dir_ / "single.exr");
  ASSERT_EQ(a.channels, b.channels);
  EXPECT_GE(a.channel_index("CryptoMaterial02.A"), 0);
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
  expect_same_crypto_header(dir_ / "merged.exr", dir_ / "single.exr");
}

class CryptomatteFarm : public FarmTest {};

// The scene asks for it and the job splits its frame: a farm renders the
// partials on two workers and the fetched frame is the local render, bitwise.
TEST_F(CryptomatteFarm, FrameSplitIntoTasksEqualsTheLocalRender) {
  const auto config = write_config(10);
  const auto scene = write_scene(40, 30, 12);
  {
    std::ifstream in(scene);
    auto doc = nlohmann::json::parse(in);
    doc["render"]["aovs"] = {"cryptomatte", "albedo"};
    in.close();
    std::ofstream(scene) << doc.dump(2);
  }
  start_server(config);
  start_worker("w1", config);
  start_worker("w2", config);
  // 12 samples in tasks of 5: [0,5) [5,10) [10,12).
  const long long id = submit(scene.string() + " --frames 3 --split 5 --name crypto");
  const auto j = wait_finished(id, 120);
  ASSERT_EQ(j.at("counts").at("done"), 3) << j.dump();
  const RunResult f = farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string()));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const auto local = dir_ / "local.exr";
  const RunResult r =
      run(fmt::format("render {} -o {} --frame 3 -q", scene.string(), local.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto fetched = dir_ / "frames/crypto.0003.exr";
  expect_bitwise_equal(fetched, local);
  const LayeredImage a = read_exr(fetched);
  EXPECT_GE(a.channel_index("CryptoObject02.A"), 0);
  expect_same_crypto_header(fetched, local);
}

}  // namespace
}  // namespace vesper::test
