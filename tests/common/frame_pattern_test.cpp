// Frame patterns in file names (common/frame_pattern.h).
#include <gtest/gtest.h>

#include "common/frame_pattern.h"

namespace vesper {
namespace {

TEST(FramePattern, TheFirstRunOfTheFileNameIsTheZeroPaddedFrame) {
  EXPECT_EQ(frame_path("a/smoke.####.vdb", 7), "a/smoke.0007.vdb");
  EXPECT_EQ(frame_path("smoke.#.vdb", 12), "smoke.12.vdb");  // longer than the run: whole
  EXPECT_EQ(frame_path("s.##.vdb", -3), "s.-3.vdb");
  EXPECT_EQ(frame_path("s.##_##.exr", 5), "s.05_##.exr");  // only the first run
  EXPECT_EQ(frame_path("still.vdb", 5), "still.vdb");
  EXPECT_TRUE(has_frame_pattern("a/s.###.obj"));
  EXPECT_FALSE(has_frame_pattern("a/s.obj"));
  EXPECT_FALSE(has_frame_pattern("take#2/s.obj"));  // not in folder names
  EXPECT_EQ(find_frame_pattern("ab###c"), (std::pair<size_t, size_t>{2, 3}));
}

}  // namespace
}  // namespace vesper
