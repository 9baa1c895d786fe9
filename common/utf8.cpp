#include "common/utf8.h"

#include <algorithm>

namespace vesper {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

bool continuation(std::string_view s, size_t at, unsigned char lo = 0x80, unsigned char hi = 0xBF) {
  if (at >= s.size()) return false;
  const auto c = static_cast<unsigned char>(s[at]);
  return c >= lo && c <= hi;
}

}  // namespace

size_t utf8_character_length(std::string_view s, size_t at) {
  if (at >= s.size()) return 0;
  const auto c = static_cast<unsigned char>(s[at]);
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return continuation(s, at + 1) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    // E0: no overlong forms; ED: no UTF-16 surrogates.
    const unsigned char lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    return continuation(s, at + 1, lo, hi) && continuation(s, at + 2) ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    // F0: no overlong forms; F4: nothing beyond U+10FFFF.
    const unsigned char lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    return continuation(s, at + 1, lo, hi) && continuation(s, at + 2) && continuation(s, at + 3)
               ? 4
               : 0;
  }
  return 0;
}

bool is_valid_utf8(std::string_view s) {
  for (size_t i = 0; i < s.size();) {
    const size_t n = utf8_character_length(s, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string utf8_safe(std::string_view s, size_t max_bytes) {
  std::string out;
  out.reserve(std::min(s.size(), max_bytes));
  for (size_t i = 0; i < s.size();) {
    const size_t n = utf8_character_length(s, i);
    const std::string_view character = n ? s.substr(i, n) : kReplacement;
    if (out.size() + character.size() > max_bytes) break;
    out += character;
    i += n ? n : 1;
  }
  return out;
}

std::string utf8_tail(std::string_view s, size_t max_bytes) {
  if (s.size() <= max_bytes) return utf8_safe(s);
  size_t start = s.size() - max_bytes;
  // Skip the continuation bytes of a character cut by the start (at most 3).
  for (int i = 0;
       i < 3 && start < s.size() && (static_cast<unsigned char>(s[start]) & 0xC0) == 0x80; ++i)
    ++start;
  return utf8_safe(s.substr(start), max_bytes);
}

}  // namespace vesper
