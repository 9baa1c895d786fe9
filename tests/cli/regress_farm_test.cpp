// vesper regress --server: the suite rendered on a farm of real `vesper
// server` and `vesper worker` processes on 127.0.0.1. Renders equal to the
// local ones pass against goldens made with --local (bit for bit: Z 0), a
// second identical run is reused and says so, a task that fails on the
// worker makes its scene an `error` with the task's log, and a server that is
// not there is exit 2.
#include <fmt/format.h>

#include "tests/cli/farm_test_fixture.h"

namespace fs = std::filesystem;

namespace vesper::test {
namespace {

class RegressFarmTest : public FarmTest {
 protected:
  RegressFarmTest() {
    const fs::path cornell = fs::path(VESPER_SOURCE_DIR) / "scenes/cornell";
    fs::create_directories(dir_ / "box");
    fs::copy_file(cornell / "scene.json", dir_ / "box/scene.json");
    fs::copy_file(cornell / "cube.obj", dir_ / "box/cube.obj");
    std::ofstream(dir_ / "suite.json")
        << R"({"format": "vesper-suite/1", "scenes": [{"name": "box", "scene": "box/scene.json",)"
        << R"( "spp": 16, "scale": 0.125}]})";
  }
  std::string regress(const std::string& args) {
    return fmt::format("regress {} --goldens {} {}", (dir_ / "suite.json").string(),
                       (dir_ / "goldens").string(), args);
  }
  nlohmann::json report(const std::string& name) {
    return nlohmann::json::parse(slurp(dir_ / name / "report.json"));
  }
};

TEST_F(RegressFarmTest, PassesAgainstLocalGoldensThenReportsTheReuse) {
  ASSERT_EQ(run(regress("--update-goldens --seed 5 -q")).exit_code, 0);
  const auto config = write_config(10);
  start_server(config);
  start_worker("w1", config);

  const RunResult first = farm(regress("--seed 5 --report " + (dir_ / "r1").string()));
  ASSERT_EQ(first.exit_code, 0) << first.out << first.err;
  EXPECT_NE(first.out.find("pass  box"), std::string::npos) << first.out;
  EXPECT_EQ(first.out.find("(reused: not re-rendered)"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("render times: shown, not judged"), std::string::npos) << first.out;
  const nlohmann::json r1 = report("r1");
  EXPECT_EQ(r1.at("server"), url_);
  const nlohmann::json& box = r1.at("scenes").at(0);
  EXPECT_EQ(box.at("reused"), false);
  EXPECT_TRUE(box.at("channels_added").empty()) << box.dump();
  EXPECT_TRUE(box.at("channels_missing").empty()) << box.dump();
  // The farm rendered what --local renders (variance, per-layer variance,
  // seed, film scale): the same pixels.
  EXPECT_EQ(box.at("layers").at(0).at("max_abs_z"), 0.0) << box.dump();
  EXPECT_GT(box.at("new_seconds").get<double>(), 0);  // the EXR's own render time

  const RunResult second = farm(regress("--seed 5 --report " + (dir_ / "r2").string()));
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_NE(second.out.find("pass  box"), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("(reused: not re-rendered)"), std::string::npos) << second.out;
  EXPECT_EQ(report("r2").at("scenes").at(0).at("reused"), true);
  EXPECT_NE(slurp(dir_ / "r2/index.html").find("reused: not re-rendered"), std::string::npos);

  // Goldens written from the farm compare with a later --local run; its
  // time was measured on the farm, so the local run does not judge against it.
  const RunResult update = farm(regress("--update-goldens --seed 6 -q"));
  ASSERT_EQ(update.exit_code, 0) << update.out << update.err;
  EXPECT_NE(slurp(dir_ / "goldens/box.json").find("\"timing\": \"farm\""), std::string::npos);
  const RunResult local = run(regress("--seed 6 --repeats 1"));
  EXPECT_EQ(local.exit_code, 0) << local.out << local.err;
  EXPECT_NE(local.err.find("the golden was timed on the farm"), std::string::npos) << local.err;
}

TEST_F(RegressFarmTest, AFailedTaskIsAnErrorWithItsLog) {
  ASSERT_EQ(run(regress("--update-goldens -q")).exit_code, 0);
  const fs::path broken = dir_ / "broken-vesper";
  std::ofstream(broken) << "#!/bin/sh\necho 'boom: the renderer broke' >&2\nexit 1\n";
  fs::permissions(broken, fs::perms::owner_all);
  const auto config = write_config(10);
  start_server(config);
  start_worker("broken", config, {"--renderer", broken.string()});

  const RunResult r = farm(regress("--report " + (dir_ / "r").string() + " -q"));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("error  box"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("failed after 3 attempts"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("boom: the renderer broke"), std::string::npos) << r.out;
  const nlohmann::json box = report("r").at("scenes").at(0);
  EXPECT_EQ(box.at("verdict"), "error");
  EXPECT_NE(box.at("reasons").at(0).get<std::string>().find("boom"), std::string::npos)
      << box.dump();
}

TEST_F(RegressFarmTest, NoServerOrLocalOnlyFlagsAreExitTwo) {
  ASSERT_EQ(run(regress("--update-goldens -q")).exit_code, 0);
  const RunResult none = run(regress("--server http://127.0.0.1:1 --token t"));
  EXPECT_EQ(none.exit_code, 2) << none.out << none.err;
  EXPECT_NE(none.err.find("cannot reach the server"), std::string::npos) << none.err;
  EXPECT_EQ(run(regress("--server http://127.0.0.1:1 --repeats 2")).exit_code, 2);
  EXPECT_EQ(run(regress("--token t")).exit_code, 2);  // --token needs --server
}

}  // namespace
}  // namespace vesper::test
