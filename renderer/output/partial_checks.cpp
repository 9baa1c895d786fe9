#include "renderer/output/partial_checks.h"

#include <stdexcept>

#include "renderer/output/film_sums.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper::partial_checks {

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw PartialError(source + ": " + what);
}

std::string range_text(const Partial& p) {
  return "[" + std::to_string(p.sample_begin) + ", " + std::to_string(p.sample_end) + ")";
}

size_t pixel_count(const Partial& p) { return size_t(p.width) * size_t(p.height); }
size_t sum_count(const Partial& p) { return pixel_count(p) * p.channels.size(); }

void check_sums_size(const Partial& p) {
  if (p.sums.size() != sum_count(p))
    fail(p.source, "holds " + std::to_string(p.sums.size()) + " sums, expected " +
                       std::to_string(p.width) + "x" + std::to_string(p.height) + "x" +
                       std::to_string(p.channels.size()) + " = " + std::to_string(sum_count(p)));
  if (p.counts.size() != pixel_count(p) * size_t(kSampleStreams))
    fail(p.source, "holds " + std::to_string(p.counts.size()) + " sample counts, expected " +
                       std::to_string(pixel_count(p) * size_t(kSampleStreams)));
  const size_t streams = pixel_count(p) * size_t(kSampleStreams) * p.streamed.size();
  if (p.stream_sums.size() != streams)
    fail(p.source, "holds " + std::to_string(p.stream_sums.size()) + " stream sums, expected " +
                       std::to_string(streams));
  try {
    (void)find_derived_channels(p.channels, p.streamed);
  } catch (const std::invalid_argument& e) {
    fail(p.source, e.what());
  }
}

}  // namespace vesper::partial_checks
