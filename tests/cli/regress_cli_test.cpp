// vesper regress from the command line: goldens, a pass at another seed, a
// real change flagged, a 30 % slowdown flagged through a sleeping --renderer
// wrapper, and the exit codes cron relies on (0 pass, 1 regressed or error,
// 2 bad input).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
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

// A renderer that takes `seconds` of wall time: the real render, then a wait
// until `seconds` have passed since it started.
void write_timed_renderer(const fs::path& file, double seconds) {
  std::ofstream(file) << "#!/bin/sh\nstart=$(date +%s.%N)\n"
                      << VESPER_BINARY << " \"$@\"\nstatus=$?\n"
                      << "sleep $(awk \"BEGIN { d = $start + " << seconds
                      << " - $(date +%s.%N); print (d > 0 ? d : 0) }\")\nexit $status\n";
  fs::permissions(file, fs::perms::owner_all);
}

// The issue's power test: a renderer 30 % slower is flagged under the
// default max_slowdown of 1.2, judged on the fastest of the repeats.
// Wall times of real renders cannot tell 1.3 from 1.2 on a shared machine:
// on the 2-core VM this was written on (load average 6-8), one 64x64 render's
// wall time moved between 0.92 and 1.88 s within a 12-second window, and a
// sleep of 0.3x each render flagged only 2 runs in 4 (measured ratios down to
// 1.12). So the renderer here takes a fixed wall time, the real render (about
// a second) included: 2.5 s for the golden, 1.3 x 2.5 s for the slow one.
TEST_F(RegressCli, AThirtyPercentSlowdownIsFlaggedUnderTheDefaultLimit) {
  write_suite("slow.json", R"("spp": 64, "scale": 0.25)");
  write_timed_renderer(dir_ / "vesper-2.5s", 2.5);
  write_timed_renderer(dir_ / "vesper-3.25s", 1.3 * 2.5);
  const std::string timing = " --threads 1 --repeats 3 -q --renderer ";
  ASSERT_EQ(run(suite("slow.json") + " --goldens " + goldens() + " --update-goldens" + timing +
                (dir_ / "vesper-2.5s").string())
                .exit_code,
            0);
  const RunResult slow = run(suite("slow.json") + " --goldens " + goldens() + timing +
                             (dir_ / "vesper-3.25s").string());
  EXPECT_EQ(slow.exit_code, 1) << slow.out << slow.err;
  EXPECT_NE(slow.out.find("regressed  box"), std::string::npos) << slow.out;
  EXPECT_NE(slow.out.find("render time"), std::string::npos) << slow.out;
  std::smatch ratio;  // 1.3, less the shell's few milliseconds on both sides
  ASSERT_TRUE(std::regex_search(slow.out, ratio, std::regex(R"(is ([0-9.]+)x the golden's)")))
      << slow.out;
  EXPECT_NEAR(std::stod(ratio[1]), 1.3, 0.05) << slow.out;
  EXPECT_NE(slow.out.find("(limit max_slowdown 1.2)"), std::string::npos) << slow.out;
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
