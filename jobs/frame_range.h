#pragma once
// Frame lists as users write them: "1-100", "1-100x5" (every 5th), "1,5,9",
// and combinations ("1-10,20,30-40x2"). Frames are returned sorted and
// unique.
#include <stdexcept>
#include <string>
#include <vector>

namespace vesper {

class FrameRangeError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Throws FrameRangeError naming the bad piece ("'5-1': end 1 is before start 5").
std::vector<int> parse_frame_range(const std::string& text);

// Sorted unique frames as parse_frame_range reads them back, runs of
// consecutive frames as ranges: {1, 2, 3, 7} -> "1-3,7" ("" for none).
std::string format_frame_list(const std::vector<int>& frames);

}  // namespace vesper
