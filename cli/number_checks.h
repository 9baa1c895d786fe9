#pragma once
// The checks behind main.cpp's numeric flag validators, apart from CLI11 (a
// heavy header kept to main.cpp). CLI11's PositiveNumber / NonNegativeNumber
// name the whole double range ("not in range 0 to 1797693...", 309 digits)
// and let "-1" wrap in an unsigned option; these name the bound and refuse
// signs where they do not fit. Each returns "" when `s` is fine, else the message.
#include <string>

namespace vesper::cli {

// A whole number >= min ("--spp 0: must be at least 1, got 0"). A number too
// large for long long passes: the option's own conversion checks its range.
std::string check_at_least(const std::string& s, long long min);
// A number > 0.
std::string check_greater_than_zero(const std::string& s);

}  // namespace vesper::cli
