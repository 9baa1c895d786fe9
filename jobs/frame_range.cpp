#include "jobs/frame_range.h"

#include <algorithm>
#include <charconv>

namespace vesper {
namespace {

constexpr int kMaxFrames = 1'000'000;

int parse_int(std::string_view s, const std::string& piece, const char* what) {
  int v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
    throw FrameRangeError("'" + piece + "': expected an integer " + what + ", got '" +
                          std::string(s) + "'");
  return v;
}

}  // namespace

std::vector<int> parse_frame_range(const std::string& text) {
  std::vector<int> frames;
  if (text.empty())
    throw FrameRangeError("empty frame range (expected e.g. 1-100, 1-100x5 or 1,5,9)");
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string piece = text.substr(start, comma - start);
    if (piece.empty()) throw FrameRangeError("'" + text + "': empty element between commas");
    // A leading '-' is a negative start frame, not a range separator.
    const size_t dash = piece.find('-', 1);
    if (dash == std::string::npos) {
      frames.push_back(parse_int(piece, piece, "frame"));
    } else {
      const size_t x = piece.find('x', dash);
      const int first = parse_int(std::string_view(piece).substr(0, dash), piece, "start");
      const int last =
          parse_int(std::string_view(piece).substr(
                        dash + 1, (x == std::string::npos ? piece.size() : x) - dash - 1),
                    piece, "end");
      const int step = x == std::string::npos
                           ? 1
                           : parse_int(std::string_view(piece).substr(x + 1), piece, "step");
      if (last < first)
        throw FrameRangeError("'" + piece + "': end " + std::to_string(last) + " is before start " +
                              std::to_string(first));
      if (step <= 0)
        throw FrameRangeError("'" + piece + "': step must be positive, got " +
                              std::to_string(step));
      // In 64 bits: `last - first` overflows an int for ranges of 2^31 frames or more.
      if (((long long)last - first) / step + 1 + (long long)frames.size() > kMaxFrames)
        throw FrameRangeError("'" + piece + "': more than " + std::to_string(kMaxFrames) +
                              " frames");
      for (long long f = first; f <= last; f += step) frames.push_back(int(f));
    }
    start = comma + 1;
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

std::string format_frame_list(const std::vector<int>& frames) {
  std::string out;
  for (size_t i = 0; i < frames.size();) {
    size_t j = i;
    while (j + 1 < frames.size() && (long long)frames[j + 1] == (long long)frames[j] + 1) ++j;
    if (!out.empty()) out += ",";
    out += std::to_string(frames[i]);
    if (j > i) out += "-" + std::to_string(frames[j]);
    i = j + 1;
  }
  return out;
}

}  // namespace vesper
