// `vesper bench --quick` on the project's real benchmark set, as a user runs
// it: every output complete and consistent, errors fall with spp, the second
// run reads every reference from the cache; and the bad-input exits.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "measure/cycles_renderer.h"
#include "tests/common/cli_runner.h"

namespace vesper::measure {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class BenchCli : public test::CliTest {
 protected:
  BenchCli() : CliTest("bench") {}
  test::RunResult quick(const std::string& out) {
    return run("--quick -o " + (dir_ / out).string() + " --refs " + (dir_ / "refs").string() +
               " --scenes " + scenes_ + " --threads 2");
  }
  json bench_json(const std::string& out) {
    return json::parse(test::slurp(dir_ / out / "bench.json"));
  }
  std::string scenes_ = (fs::path(VESPER_SOURCE_DIR) / "bench/scenes.json").string();
};

size_t count_lines(const std::string& s) {
  std::istringstream in(s);
  std::string line;
  size_t n = 0;
  while (std::getline(in, line)) n += !line.empty();
  return n;
}

void expect_png(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  ASSERT_TRUE(in) << p;
  std::vector<unsigned char> px(size_t(in->spec().image_pixels()) * size_t(in->spec().nchannels));
  EXPECT_TRUE(in->read_image(0, 0, 0, -1, OIIO::TypeDesc::UINT8, px.data())) << p;
  EXPECT_GT(in->spec().width, 100);
}

TEST_F(BenchCli, QuickRunIsCompleteAndTheSecondRunHitsTheCache) {
  const test::RunResult first = quick("a");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("time to 0.01"), std::string::npos) << first.out;  // the table
  const json a = bench_json("a");
  EXPECT_EQ(a["format"], "vesper-bench-report/1");
  ASSERT_GE(a["scenes"].size(), 6u);
  size_t rows = 0, measured = 0;
  for (const json& s : a["scenes"]) {
    if (s["skipped"].get<bool>()) {  // only the smoke scene may be, without ../shared/data
      EXPECT_EQ(s["name"], "smoke");
      EXPECT_NE(s["note"].get<std::string>().find("smoke.vdb"), std::string::npos);
      continue;
    }
    ++measured;
    const json& r = s["renderers"].at(0);
    EXPECT_EQ(r["renderer"], "vesper");
    EXPECT_FALSE(r["reference"]["cache_hit"].get<bool>());
    EXPECT_GT(r["reference"]["noise_floor"].get<double>(), 0);
    const json& m = r["measurements"];
    ASSERT_EQ(m.size(), 3u) << s["name"];
    rows += m.size();
    // relMSE falls with spp: expected ~ v/1 + v/16 at 1 spp and v/4 + v/16 at 4 spp.
    EXPECT_LT(m[2]["relmse"].get<double>(), m[0]["relmse"].get<double>()) << s["name"];
    EXPECT_EQ(r["time_to_error"].size(), 2u);
    expect_png(dir_ / "a" / ("plot-" + s["name"].get<std::string>() + ".png"));
  }
  EXPECT_GE(measured, 5u);
  EXPECT_EQ(count_lines(test::slurp(dir_ / "a/bench.csv")), rows + 1);  // + the header
  EXPECT_TRUE(fs::exists(dir_ / "a/table.md"));

  const test::RunResult second = quick("b");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  for (const json& s : bench_json("b")["scenes"]) {
    if (s["skipped"].get<bool>()) continue;
    EXPECT_TRUE(s["renderers"][0]["reference"]["cache_hit"].get<bool>()) << s["name"];
  }
}

TEST_F(BenchCli, BadInputExitsTwoAndSaysWhy) {
  const auto out = " -o " + (dir_ / "o").string() + " --scenes " + scenes_;
  const test::RunResult other = run("--quick --compare mitsuba" + out);
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("accepted: cycles"), std::string::npos) << other.err;
  std::ofstream(dir_ / "bad.json") << R"({"format": "vesper-bench/1", "scenes": [{"name": 3}]})";
  const test::RunResult bad =
      run("--quick -o " + (dir_ / "o").string() + " --scenes " + (dir_ / "bad.json").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.json: /scenes/0"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "o/bench.json"));
}

}  // namespace
}  // namespace vesper::measure

namespace vesper::measure {
namespace {

// With blender: Cornell alone, quick, against Cycles: both renderers measured,
// the comparison in bench.json. Without it (CI): exit 2 saying how to install it.
TEST_F(BenchCli, CompareCyclesMeasuresBothOrSaysHowToInstallBlender) {
  std::ofstream(dir_ / "one.json")
      << R"({"format": "vesper-bench/1",
    "quick": {"width": 16, "height": 16, "spp": [1, 4], "reference_spp": 16},
    "scenes": [{"name": "cornell", "path": ")"
      << (fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/scene.json").string()
      << R"(", "kind": "surface", "width": 64, "height": 64,
    "spp": [1], "reference_spp": 4}]})";
  const test::RunResult r =
      run("--quick --compare cycles --threads 2 -o " + (dir_ / "c").string() + " --refs " +
          (dir_ / "crefs").string() + " --scenes " + (dir_ / "one.json").string());
  if (find_executable("blender").empty()) {
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("scripts/setup --peers"), std::string::npos) << r.err;
    return;
  }
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json c = bench_json("c");
  const json& scene = c["scenes"][0];
  ASSERT_EQ(scene["renderers"].size(), 2u);
  EXPECT_EQ(scene["renderers"][1]["renderer"], "cycles");
  EXPECT_EQ(scene["renderers"][1]["measurements"].size(), 2u);
  ASSERT_EQ(scene["comparisons"].size(), 1u);
  // 16 spp references of a 16x16 image: only a gross mistranslation leaves this band.
  const double mean_ratio = scene["comparisons"][0]["references"]["mean_ratio"].get<double>();
  EXPECT_GT(mean_ratio, 0.8) << scene["comparisons"][0].dump();
  EXPECT_LT(mean_ratio, 1.25) << scene["comparisons"][0].dump();
}

}  // namespace
}  // namespace vesper::measure
