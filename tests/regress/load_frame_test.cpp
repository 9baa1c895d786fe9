// A missing or corrupt golden (or new image) is an `error` result with a
// reason that names the file, never an exception; good files compare.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "regress/load_frame.h"
#include "regress_dir_test.h"
#include "renderer/output/exr_io.h"
#include "synthetic_images.h"

namespace vesper::regress {
namespace {

namespace fs = std::filesystem;

class LoadFrameTest : public test::RegressDirTest {
 protected:
  void SetUp() override {
    write_exr(test::synthetic_image(16, 16, {{"beauty"}}, 1), dir_ / "golden.exr");
    write_exr(test::synthetic_image(16, 16, {{"beauty"}}, 2), dir_ / "new.exr");
  }
};

TEST_F(LoadFrameTest, GoodFilesCompareAndCarryTheirPaths) {
  const SceneResult r =
      compare_files("cornell", dir_ / "golden.exr", dir_ / "new.exr", nullptr, {});
  EXPECT_EQ(r.verdict, Verdict::Pass);
  EXPECT_EQ(r.name, "cornell");
  EXPECT_EQ(r.golden_image, (dir_ / "golden.exr").string());
  EXPECT_EQ(r.new_image, (dir_ / "new.exr").string());
  EXPECT_EQ(r.layers.size(), 1u);
}

TEST_F(LoadFrameTest, AMissingGoldenIsAnErrorThatSaysHowToCreateIt) {
  const fs::path golden = dir_ / "missing.exr";
  const SceneResult r = compare_files("cornell", golden, dir_ / "new.exr", nullptr, {});
  EXPECT_EQ(r.verdict, Verdict::Error);
  EXPECT_EQ(r.name, "cornell");
  ASSERT_EQ(r.reasons.size(), 1u);
  EXPECT_EQ(r.reasons[0],
            "no golden image " + golden.string() + " (run with --update-goldens to create it)");
  EXPECT_TRUE(r.layers.empty());
}

TEST_F(LoadFrameTest, CorruptAndTruncatedImagesAreErrorsNamingTheFile) {
  std::ofstream(dir_ / "garbage.exr") << "this is not an image";
  const SceneResult g = compare_files("c", dir_ / "garbage.exr", dir_ / "new.exr", nullptr, {});
  EXPECT_EQ(g.verdict, Verdict::Error);
  ASSERT_EQ(g.reasons.size(), 1u);
  EXPECT_EQ(g.reasons[0].rfind("golden image unreadable: ", 0), 0u) << g.reasons[0];
  EXPECT_NE(g.reasons[0].find((dir_ / "garbage.exr").string()), std::string::npos) << g.reasons[0];

  const auto size = fs::file_size(dir_ / "new.exr");
  fs::copy_file(dir_ / "new.exr", dir_ / "truncated.exr");
  fs::resize_file(dir_ / "truncated.exr", size / 2);
  const SceneResult t =
      compare_files("c", dir_ / "golden.exr", dir_ / "truncated.exr", nullptr, {});
  EXPECT_EQ(t.verdict, Verdict::Error);
  ASSERT_EQ(t.reasons.size(), 1u);
  EXPECT_EQ(t.reasons[0].rfind("new render image unreadable: ", 0), 0u) << t.reasons[0];
}

TEST_F(LoadFrameTest, BothMissingAreBothReported) {
  SceneResult r;
  EXPECT_FALSE(load_frame(dir_ / "a.exr", "golden", r));
  EXPECT_FALSE(load_frame(dir_ / "b.exr", "new render", r));
  EXPECT_EQ(r.verdict, Verdict::Error);
  EXPECT_EQ(r.reasons.size(), 2u);
  EXPECT_EQ(r.reasons[1], "no new render image " + (dir_ / "b.exr").string());
}

}  // namespace
}  // namespace vesper::regress
