// `vesper vdb` as a user runs it: real process, real files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../common/cli_runner.h"
#include "renderer/volume/vdb_io.h"

namespace fs = std::filesystem;

namespace {

using vesper::test::RunResult;
using vesper::test::slurp;

class VdbCli : public vesper::test::CliTest {
 protected:
  VdbCli() : CliTest("vdb") {}
};

TEST_F(VdbCli, CloudWritesAFogVolumeThatLoadsAndInfoDescribesIt) {
  const fs::path vdb = dir_ / "cloud.vdb";
  const RunResult r = run("cloud -o " + vdb.string() + " --resolution 40 --seed 7");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, vdb.string() + "\n");
  const auto grid = vesper::load_vdb_grid(vdb, "density");
  EXPECT_FALSE(grid->active_box().empty());
  EXPECT_GT(grid->max_value(), 0.9f);
  EXPECT_LE(grid->max_value(), 1.0f);
  // 2.56 world units across at any resolution.
  EXPECT_NEAR(grid->index_to_world().apply_vector({40, 0, 0}).x, 2.56, 1e-9);

  const RunResult info = run("info " + vdb.string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("density (float, fog volume)"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("active voxels: "), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("value range: ["), std::string::npos) << info.out;

  // Same seed, same bytes in the grid; the output is replaced atomically.
  const RunResult again = run("cloud -o " + vdb.string() + " --resolution 40 --seed 7 -q");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const auto grid2 = vesper::load_vdb_grid(vdb, "density");
  EXPECT_EQ(grid2->max_value(), grid->max_value());
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(VdbCli, InfoOnAMissingFileFailsNamingIt) {
  const fs::path missing = dir_ / "no-such-smoke.vdb";
  const RunResult r = run("info " + missing.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(VdbCli, CloudIntoAMissingDirectoryIsBadInput) {
  const RunResult r = run("cloud -o " + (dir_ / "nope" / "c.vdb").string() + " --resolution 16");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot write"), std::string::npos) << r.err;
}

TEST_F(VdbCli, CloudFramesWriteAnEvolvingSequenceThatLoads) {
  const RunResult r =
      run("cloud --frames 1-3 -q --resolution 24 -o " + (dir_ / "cloud.####.vdb").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, (dir_ / "cloud.0001.vdb").string() + "\n" + (dir_ / "cloud.0002.vdb").string() +
                       "\n" + (dir_ / "cloud.0003.vdb").string() + "\n");
  for (int f = 1; f <= 3; ++f) {
    const auto grid =
        vesper::load_vdb_grid(dir_ / ("cloud.000" + std::to_string(f) + ".vdb"), "density");
    EXPECT_FALSE(grid->active_box().empty()) << f;
  }
  // Frame 1 is the still cloud.
  ASSERT_EQ(run("cloud -q --resolution 24 -o " + (dir_ / "still.vdb").string()).exit_code, 0);
  const auto still = vesper::load_vdb_grid(dir_ / "still.vdb", "density");
  const auto first = vesper::load_vdb_grid(dir_ / "cloud.0001.vdb", "density");
  EXPECT_EQ(still->max_value(), first->max_value());
  EXPECT_EQ(still->active_box().min, first->active_box().min);
  EXPECT_EQ(still->active_box().max, first->active_box().max);
  // Several frames need a pattern.
  const RunResult bad = run("cloud --frames 1-2 --resolution 16 -o " + (dir_ / "c.vdb").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("frame pattern"), std::string::npos) << bad.err;
}

}  // namespace
