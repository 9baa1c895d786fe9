// `vesper render --aov cryptomatte` end to end: the EXR gets the Crypto
// layers, a partial render refuses them (exit 2, nothing written), and
// `vesper comp` reads such a file like any other: the same composite as
// from the file without them, and only the graded beauty in its EXR.
#include <gtest/gtest.h>

#include <fstream>

#include "renderer/output/exr_io.h"
#include "tests/common/cli_runner.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;

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

TEST_F(CryptomatteCli, PartialRenderRefusesIt) {
  const RunResult r = render("a.vpartial", "--aov cryptomatte --partial --sample-end 2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cryptomatte"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("partial"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "a.vpartial"));
}

// The scene asks for it and the job would split frames: refused before
// anything is uploaded (the server, which does not read scenes, could not).
TEST_F(CryptomatteCli, SubmitRefusesSplittingACryptomatteScene) {
  std::ofstream(dir_ / "scene.json") << R"({"format": "vesper-scene/1",
    "camera": {"type": "perspective", "from": [0, 0, 4], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 30},
    "film": {"width": 8, "height": 8}, "render": {"spp": 32, "aovs": ["cryptomatte"]},
    "materials": {"m": {"type": "diffuse"}}, "shapes": []})";
  const std::string submit =
      "submit " + q(dir_ / "scene.json") + " --server http://127.0.0.1:9 --token t --dry-run ";
  const RunResult split = run(submit + "--split 8");
  EXPECT_EQ(split.exit_code, 2);
  EXPECT_NE(split.err.find("--split"), std::string::npos) << split.err;
  EXPECT_NE(split.err.find("cryptomatte"), std::string::npos) << split.err;
  // Whole frames pass the check (and then fail to reach the absent server).
  const RunResult whole = run(submit + "--split 32");
  EXPECT_EQ(whole.err.find("cryptomatte"), std::string::npos) << whole.err;
  EXPECT_NE(whole.err.find("cannot reach"), std::string::npos) << whole.err;
}

}  // namespace
}  // namespace vesper::test
