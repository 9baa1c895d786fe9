// The traps a new user walks into, run against the real binary: usage errors
// exit 2 (cli/README.md), numeric flags name their bound, unknown flags get a
// "did you mean", -o picks the format by extension and fills #### with the
// frame, the output folder is checked before rendering, -q on every command.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "../common/cli_runner.h"
#include "renderer/output/exr_io.h"

namespace fs = std::filesystem;

namespace {

using vesper::test::RunResult;
using vesper::test::slurp;

class CliTraps : public vesper::test::CliTest {
 protected:
  CliTraps() : CliTest("") {}
  const std::string kCornell = std::string(VESPER_SOURCE_DIR) + "/scenes/cornell/scene.json";
  std::string render(const std::string& args) { return "render " + kCornell + " " + args; }
  std::string out(const std::string& name) { return (dir_ / name).string(); }

  // The help of every leaf command `vesper --help` lists, recursively ("vdb cloud", ...).
  std::map<std::string, std::string> command_help(const std::string& prefix = "") {
    const std::string help = run(prefix + " --help").out;
    const size_t at = help.find("Subcommands:\n");
    if (at == std::string::npos) return {{prefix, help}};
    std::map<std::string, std::string> leaves;
    std::istringstream lines(help.substr(at + 13));
    std::string line, name;
    while (std::getline(lines, line) && line.rfind("  ", 0) == 0) {
      std::istringstream(line) >> name;
      leaves.merge(command_help(prefix.empty() ? name : prefix + " " + name));
    }
    return leaves;
  }
};

TEST_F(CliTraps, UsageErrorsExitTwo) {
  for (const std::string& args : std::vector<std::string>{
           "", "rendr", "render", "render " + kCornell, render("-o " + out("x.exr") + " extra"),
           "render " + out("missing.json") + " -o " + out("x.exr"),
           render("-o " + out("x.exr") + " --threads many"), "vdb", "vdb clod", "status --bogus",
           "merge -o " + out("x.exr")}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << "vesper " << args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << "vesper " << args << ": " << r.out;
    EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
  }
  EXPECT_EQ(run("--help").exit_code, 0);
  EXPECT_EQ(run("render --help").exit_code, 0);
  EXPECT_EQ(run("--version").exit_code, 0);
}

TEST_F(CliTraps, ZeroSamplesAndNegativeSeedsNameTheBound) {
  const RunResult spp = run(render("-o " + out("x.exr") + " --spp 0"));
  EXPECT_EQ(spp.exit_code, 2);
  EXPECT_NE(spp.err.find("--spp: must be at least 1"), std::string::npos) << spp.err;
  EXPECT_EQ(spp.err.find("1797693"), std::string::npos) << "the double range leaks: " << spp.err;
  EXPECT_LT(spp.err.size(), 200u) << spp.err;

  const RunResult seed = run(render("-o " + out("x.exr") + " --seed -1"));
  EXPECT_EQ(seed.exit_code, 2);
  EXPECT_NE(seed.err.find("--seed: must be at least 0"), std::string::npos) << seed.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.exr"));

  for (const char* flag : {"--threads 0", "--sample-begin -1", "--sample-end -1"})
    EXPECT_EQ(run(render("-o " + out("x.exr") + " " + flag)).exit_code, 2) << flag;
  // The full unsigned 64-bit seed range still works.
  EXPECT_EQ(run(render("-o " + out("x.exr") + " --spp 1 -q --seed 18446744073709551615")).exit_code,
            0);
}

TEST_F(CliTraps, BadSamplingBudgetsNameTheFlagAndWriteNothing) {
  for (const char* flag : {"--noise-target 0", "--noise-target -0.1", "--time-limit 0",
                           "--min-spp 0", "--max-spp 0"}) {
    const RunResult r = run(render("-o " + out("x.exr") + " " + flag));
    EXPECT_EQ(r.exit_code, 2) << flag;
    EXPECT_NE(r.err.find(std::string(flag).substr(0, std::string(flag).find(' '))),
              std::string::npos)
        << flag << ": " << r.err;
  }
  const RunResult crossed =
      run(render("-o " + out("x.exr") + " --noise-target 0.1 --min-spp 64 --max-spp 16"));
  EXPECT_EQ(crossed.exit_code, 2);
  EXPECT_NE(crossed.err.find("--min-spp"), std::string::npos) << crossed.err;
  EXPECT_NE(crossed.err.find("cornell"), std::string::npos) << "names the scene: " << crossed.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
  // A good budget renders and records what it reached.
  ASSERT_EQ(run(render("-o " + out("a.exr") + " --noise-target 0.5 --max-spp 8 -q")).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "a.exr"));
}

TEST_F(CliTraps, UnknownFlagsAndCommandsSuggestTheNearestName) {
  const RunResult spx = run(render("-o " + out("x.exr") + " --spx 4"));
  EXPECT_EQ(spx.exit_code, 2);
  EXPECT_NE(spx.err.find("did you mean --spp?"), std::string::npos) << spx.err;
  const RunResult out_flag = run(render("--ouptut " + out("x.exr")));
  EXPECT_NE(out_flag.err.find("did you mean --output?"), std::string::npos) << out_flag.err;
  const RunResult cmd = run("rendr " + kCornell);
  EXPECT_EQ(cmd.exit_code, 2);
  EXPECT_NE(cmd.err.find("did you mean render?"), std::string::npos) << cmd.err;
  const RunResult sub = run("vdb clod -o " + out("c.vdb"));
  EXPECT_NE(sub.err.find("did you mean cloud?"), std::string::npos) << sub.err;
  // Nothing near: no guess.
  const RunResult far = run(render("-o " + out("x.exr") + " --zzzzzzzz"));
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
}

TEST_F(CliTraps, PngOutputIsTheBeautyAsCompWritesIt) {
  ASSERT_EQ(run(render("-o " + out("a.png") + " --spp 1 -q")).exit_code, 0);
  EXPECT_EQ(slurp(dir_ / "a.png").substr(0, 4), "\x89PNG");
  // The same frame as EXR, then `vesper comp` without a grade: the same image.
  ASSERT_EQ(run(render("-o " + out("a.exr") + " --spp 1 -q")).exit_code, 0);
  ASSERT_EQ(run("comp " + out("a.exr") + " -o " + out("b.png") + " -q").exit_code, 0);
  EXPECT_EQ(slurp(dir_ / "a.png"), slurp(dir_ / "b.png"));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();

  const RunResult unknown = run(render("-o " + out("a.xyz") + " --spp 1"));
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown output format"), std::string::npos) << unknown.err;
  EXPECT_EQ(run(render("-o " + out("p.png") + " --spp 1 --partial")).exit_code, 2);
}

TEST_F(CliTraps, TheOutputFolderIsCheckedBeforeRendering) {
  // A folder as the output.
  const RunResult folder = run(render("-o " + dir_.string() + " --spp 1"));
  EXPECT_EQ(folder.exit_code, 2);
  EXPECT_NE(folder.err.find("is a folder"), std::string::npos) << folder.err;
  EXPECT_EQ(folder.err.find("render:"), std::string::npos) << "rendered first: " << folder.err;

  // A folder nobody may write into (root writes anywhere a mode allows, so
  // then a filesystem that refuses new files: sysfs).
  fs::path locked = dir_ / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  if (::geteuid() == 0) locked = "/sys";
  const RunResult ro = run(render("-o " + (locked / "x.exr").string() + " --spp 1"));
  EXPECT_EQ(ro.exit_code, 2) << ro.err;
  EXPECT_NE(ro.err.find("cannot write in the output directory"), std::string::npos) << ro.err;
  EXPECT_EQ(ro.err.find("render:"), std::string::npos) << "rendered first: " << ro.err;
  EXPECT_EQ(ro.err.find("Success"), std::string::npos) << ro.err;
  fs::permissions(dir_ / "locked", fs::perms::owner_all);
}

TEST_F(CliTraps, HashesInTheOutputNameAreTheZeroPaddedFrame) {
  const RunResult r = run(render("-o " + out("seq.####.exr") + " --frame 7 --spp 1 -q"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, out("seq.0007.exr") + "\n");
  EXPECT_EQ(vesper::read_exr(dir_ / "seq.0007.exr").metadata.at("vesper:frame"), "7");
  EXPECT_EQ(run(render("-o " + out("f.##.exr") + " --frame 123 --spp 1 -q")).out,
            out("f.123.exr") + "\n");
  const RunResult no_frame = run(render("-o " + out("seq.####.exr") + " --spp 1"));
  EXPECT_EQ(no_frame.exit_code, 2);
  EXPECT_NE(no_frame.err.find("--frame"), std::string::npos) << no_frame.err;

  // merge takes the frame from the partials.
  const std::string common = " --spp 2 --frame 12 --partial -q";
  ASSERT_EQ(run(render("-o " + out("a.vpartial") + common + " --sample-end 1")).exit_code, 0);
  ASSERT_EQ(run(render("-o " + out("b.vpartial") + common + " --sample-begin 1")).exit_code, 0);
  const RunResult merged =
      run("merge -o " + out("m.####.exr") + " " + out("a.vpartial") + " " + out("b.vpartial"));
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(merged.out, out("m.0012.exr") + "\n");
}

TEST_F(CliTraps, QuietIsAcceptedByEveryCommand) {
  const auto all = command_help();
  EXPECT_GE(all.size(), 18u);
  for (const auto& [command, help] : all)
    EXPECT_NE(help.find("-q,--quiet"), std::string::npos) << "vesper " << command << " has no -q";
  // What -q does: results on stdout, nothing on stderr.
  ASSERT_EQ(run(render("-o " + out("a.exr") + " --spp 1 -q")).exit_code, 0);
  const RunResult hist = run("hist " + out("a.exr") + " --json " + out("h.json") + " -q");
  EXPECT_EQ(hist.exit_code, 0) << hist.err;
  EXPECT_TRUE(hist.err.empty()) << hist.err;
  const RunResult loud = run("hist " + out("a.exr") + " --json " + out("h.json"));
  EXPECT_FALSE(loud.err.empty());
}

// `vesper up` hides its workers' info logs while it runs, but its progress
// shows; with -q neither does, and stdout still lists the frames.
TEST_F(CliTraps, UpShowsProgressUnlessQuiet) {
  const std::string up = "up --scene " + kCornell + " --spp 1 --no-comp --data-dir " + out("farm") +
                         " -o " + out("frames");
  const RunResult loud = run(up);
  ASSERT_EQ(loud.exit_code, 0) << loud.err;
  EXPECT_NE(loud.err.find("job 1: 100%"), std::string::npos) << loud.err;
  const RunResult quiet = run(up + " -q");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.out, out("frames/cornell.0001.exr") + "\n");
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

}  // namespace
