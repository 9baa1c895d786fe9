// vesper regress from the command line: goldens, a pass at another seed, a
// real change flagged, a slowdown flagged through a sleeping --renderer
// wrapper, and the exit codes cron relies on (0 pass, 1 regressed or error,
// 2 bad input).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../common/cli_runner.h"

namespace fs = std::filesystem;

namespace {

using vesper::test::RunResult;
using vesper::test::slurp;

class RegressCli : public vesper::test::CliTest {
 protected:
  RegressCli() : CliTest("regress") {
    const fs::path cornell = fs::path(VESPER_SOURCE_DIR) / "scenes/cornell";
    fs::create_directories(dir_ / "box");
    fs::copy_file(cornell / "scene.json", dir_ / "box/scene.json");
    fs::copy_file(cornell / "cube.obj", dir_ / "box/cube.obj");
    // Render time is judged in its own test: these renders take a fraction
    // of a second, so the load of a parallel ctest run could flag them.
    write_suite("suite.json", R"("spp": 64, "scale": 0.125)", R"({"max_slowdown": 100})");
  }

  void write_suite(const std::string& name, const std::string& scene_keys,
                   const std::string& thresholds = "{}") {
    std::ofstream(dir_ / name) << R"({"format": "vesper-suite/1", "thresholds": )" << thresholds
                               << R"(, "scenes": [{"name": "box", "scene": "box/scene.json", )"
                               << scene_keys << "}]}";
  }
  // Scales the box's ceiling light (a look change every tile sees).
  void scale_light(double factor) {
    nlohmann::json scene = nlohmann::json::parse(slurp(dir_ / "box/scene.json"));
    for (auto& light : scene["lights"])
      for (auto& v : light["radiance"]) v = v.get<double>() * factor;
    std::ofstream(dir_ / "box/scene.json") << scene.dump(2);
  }
  std::string suite(const std::string& name = "suite.json") { return (dir_ / name).string(); }
  std::string goldens() { return (dir_ / "goldens").string(); }
};

TEST_F(RegressCli, GoldensThenAPassAtAnotherSeedThenALookChangeRegresses) {
  ASSERT_EQ(run(suite() + " --goldens " + goldens() + " --update-goldens --seed 1 -q").exit_code,
            0);
  EXPECT_TRUE(fs::exists(dir_ / "goldens/box.exr"));
  EXPECT_TRUE(fs::exists(dir_ / "goldens/box.json"));

  const RunResult same = run(suite() + " --goldens " + goldens() + " --seed 2 --report " +
                             (dir_ / "report").string() + " -q");
  EXPECT_EQ(same.exit_code, 0) << same.out << same.err;
  EXPECT_NE(same.out.find("pass  box"), std::string::npos) << same.out;
  EXPECT_TRUE(fs::exists(dir_ / "report/report.json"));
  EXPECT_TRUE(fs::exists(dir_ / "report/index.html"));

  scale_light(1.15);
  const RunResult changed = run(suite() + " --goldens " + goldens() + " --seed 2 -q");
  EXPECT_EQ(changed.exit_code, 1) << changed.out << changed.err;
  EXPECT_NE(changed.out.find("regressed  box"), std::string::npos) << changed.out;
  EXPECT_NE(changed.out.find("beauty"), std::string::npos) << changed.out;
  EXPECT_NE(changed.out.find("brighter"), std::string::npos) << changed.out;
}

TEST_F(RegressCli, ASlowdownThroughASleepingRendererIsFlagged) {
  ASSERT_EQ(run(suite() + " --goldens " + goldens() + " --update-goldens -q").exit_code, 0);
  const double golden =
      nlohmann::json::parse(slurp(dir_ / "goldens/box.json"))["seconds"].get<double>();
  // Half the golden's time again, against a 1.2x limit; the fastest of the
  // repeats is judged, so load spikes do not count.
  const fs::path wrapper = dir_ / "slow-vesper";
  std::ofstream(wrapper) << "#!/bin/sh\nsleep " << 0.5 * golden << "\nexec " << VESPER_BINARY
                         << " \"$@\"\n";
  fs::permissions(wrapper, fs::perms::owner_all);
  write_suite("slow.json", R"("spp": 64, "scale": 0.125)", R"({"max_slowdown": 1.2})");
  const RunResult slow = run(suite("slow.json") + " --goldens " + goldens() + " --renderer " +
                             wrapper.string() + " -q");
  EXPECT_EQ(slow.exit_code, 1) << slow.out << slow.err;
  EXPECT_NE(slow.out.find("render time"), std::string::npos) << slow.out;
}

TEST_F(RegressCli, BadInputIsExitTwoAndAMissingGoldenIsAnError) {
  write_suite("bad.json", R"("spp": 0)");
  const RunResult bad = run(suite("bad.json") + " --goldens " + goldens() + " --update-goldens");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("/scenes/0/spp"), std::string::npos) << bad.err;

  const RunResult no_dir = run(suite() + " --goldens " + (dir_ / "nowhere").string());
  EXPECT_EQ(no_dir.exit_code, 2);
  EXPECT_NE(no_dir.err.find("--update-goldens"), std::string::npos) << no_dir.err;

  fs::create_directories(dir_ / "empty");
  const RunResult missing = run(suite() + " --goldens " + (dir_ / "empty").string() + " -q");
  EXPECT_EQ(missing.exit_code, 1) << missing.out << missing.err;
  EXPECT_NE(missing.out.find("error  box"), std::string::npos) << missing.out;
}

}  // namespace
