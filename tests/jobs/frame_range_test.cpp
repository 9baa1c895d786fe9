#include <gtest/gtest.h>

#include "jobs/frame_range.h"

namespace vesper {
namespace {

TEST(FrameRange, RangesStepsListsAndCombinations) {
  EXPECT_EQ(parse_frame_range("1-5"), (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(parse_frame_range("1-20x5"), (std::vector<int>{1, 6, 11, 16}));
  EXPECT_EQ(parse_frame_range("9,1,5"), (std::vector<int>{1, 5, 9}));
  EXPECT_EQ(parse_frame_range("1-3,2,10-14x2"), (std::vector<int>{1, 2, 3, 10, 12, 14}));
  EXPECT_EQ(parse_frame_range("-2-1"), (std::vector<int>{-2, -1, 0, 1}));
  EXPECT_EQ(parse_frame_range("7"), (std::vector<int>{7}));
  EXPECT_EQ(parse_frame_range("1-100").size(), 100u);
}

TEST(FrameRange, BadInputNamesThePiece) {
  for (const char* bad :
       {"", "a", "1-", "5-1", "1-10x0", "1-10x-2", "1,,2", "1-10y2", "1.5", "1-1000000000"}) {
    try {
      parse_frame_range(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const FrameRangeError& e) {
      EXPECT_FALSE(std::string(e.what()).empty());
    }
  }
  try {
    parse_frame_range("1-3,5-1");
  } catch (const FrameRangeError& e) {
    EXPECT_NE(std::string(e.what()).find("'5-1'"), std::string::npos) << e.what();
  }
}

// Found by the job fuzz target: a range of 2^31 frames or more overflowed
// `end - start` in an int, so the limit was not applied (2^20 frames came back for
// the first; without a step, billions were pushed).
TEST(FrameRange, RangeSpanningTwoToThe31FramesIsRefused) {
  EXPECT_THROW(parse_frame_range("-2147483648-2147483647x4096"), FrameRangeError);
  EXPECT_THROW(parse_frame_range("-2147483648-2147483647x2000"), FrameRangeError);
  // The limit counts frames: one million of them is allowed, one more is not.
  EXPECT_EQ(parse_frame_range("1-1000000").size(), 1000000u);
  EXPECT_THROW(parse_frame_range("0-1000000"), FrameRangeError);
}

// `vesper up` and `fetch` name missing frames this way; it reads back.
TEST(FrameRange, FormatListsRunsAsRanges) {
  EXPECT_EQ(format_frame_list({}), "");
  EXPECT_EQ(format_frame_list({5}), "5");
  EXPECT_EQ(format_frame_list({1, 2, 3, 7, 9, 10}), "1-3,7,9-10");
  const std::vector<int> frames{0, 4, 5, 6, 100, 101};
  EXPECT_EQ(parse_frame_range(format_frame_list(frames)), frames);
}

}  // namespace
}  // namespace vesper
