#pragma once
// The equal-error table people read: per scene and renderer, the time to
// reach each relMSE target, the reference's cache state and noise floor;
// with peers, the time ratio, the project's goal and the references'
// agreement. The same rows as Markdown (table.md) and as plain text (the
// terminal).
#include <string>

#include "measure/bench_result.h"

namespace vesper::measure {

// "0.412 s" (interpolated), "~3.1 s*" (extrapolated), "< 0.02 s" (the first
// point was already below the target), "-" (unknown).
std::string format_time_to_error(const TimeToError& t);

std::string bench_table_markdown(const BenchReport& report);
std::string bench_table_text(const BenchReport& report);

}  // namespace vesper::measure
