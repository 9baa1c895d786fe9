#include "common/control_characters.h"

#include <cstdio>

#include "common/utf8.h"

namespace vesper {
namespace {

// The code point of the C1 control encoded at s[at] (2 bytes: C2 80..9F), or -1.
int c1_control_at(std::string_view s, size_t at) {
  if (at + 1 >= s.size() || static_cast<unsigned char>(s[at]) != 0xC2) return -1;
  const auto second = static_cast<unsigned char>(s[at + 1]);
  return second >= 0x80 && second <= 0x9F ? second : -1;
}

bool c0_or_del(unsigned char c) { return c < 0x20 || c == 0x7F; }

// printf into a std::string (the formats here are short).
template <typename... Args>
std::string format(const char* f, Args... args) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

}  // namespace

std::string control_character_problem(std::string_view s) {
  for (size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    const int c1 = c1_control_at(s, i);
    if (c0_or_del(c) || c1 >= 0)
      return format("contains a control character (U+%04X)", c1 >= 0 ? c1 : int(c));
  }
  return {};
}

std::string escape_control_characters(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const size_t n = utf8_character_length(s, i);
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '\n' || c == '\r' || c == '\t') {
      out += c == '\n' ? "\\n" : c == '\r' ? "\\r" : "\\t";
    } else if (c0_or_del(c) || n == 0) {
      out += format("\\x%02x", unsigned(c));
    } else if (const int c1 = c1_control_at(s, i); c1 >= 0) {
      out += format("\\u%04x", unsigned(c1));
    } else {
      out.append(s.substr(i, n));
    }
    i += n ? n : 1;
  }
  return out;
}

}  // namespace vesper
