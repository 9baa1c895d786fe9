#include "cli/number_checks.h"

#include <charconv>

namespace vesper::cli {

std::string check_at_least(const std::string& s, long long min) {
  long long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  const bool huge = ec == std::errc::result_out_of_range && !s.empty() && s[0] != '-';
  if (huge) return {};  // the option's own conversion checks its type's range
  if (ec != std::errc() || end != s.data() + s.size())
    return "expected a whole number, got '" + s + "'";
  if (v < min) return "must be at least " + std::to_string(min) + ", got " + s;
  return {};
}

std::string check_greater_than_zero(const std::string& s) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return "expected a number, got '" + s + "'";
  if (!(v > 0)) return "must be greater than 0, got " + s;
  return {};
}

}  // namespace vesper::cli
