#pragma once
// What reading, writing and merging partial renders all check, and how they
// say it. Internal to output/.
#include <string>

#include "renderer/output/partial_io.h"

namespace vesper::partial_checks {

[[noreturn]] void fail(const std::string& source, const std::string& what);
std::string range_text(const Partial& p);
size_t pixel_count(const Partial& p);
size_t sum_count(const Partial& p);
// The sums, stream sums and counts have the sizes the header promises.
void check_sums_size(const Partial& p);

}  // namespace vesper::partial_checks
