#pragma once
// UTF-8 that is safe to put in JSON and to cut: nlohmann refuses to dump a
// string that is not valid UTF-8 (the server answered 500 when an error
// message quoted an invalid byte of a request, or was cut inside a
// character), so text that comes from outside is repaired (each invalid
// byte becomes U+FFFD) and shortened at character boundaries only.
#include <cstddef>
#include <string>
#include <string_view>

namespace vesper {

// Bytes of the well-formed UTF-8 character starting at s[at] (1 to 4), or 0
// when the bytes there are not one (overlong forms and surrogates included).
size_t utf8_character_length(std::string_view s, size_t at);

bool is_valid_utf8(std::string_view s);

// `s` with every byte that does not belong to a well-formed character
// replaced by U+FFFD, then cut to at most `max_bytes` at a character boundary.
std::string utf8_safe(std::string_view s, size_t max_bytes = std::string_view::npos);

// The end of `s`: at most `max_bytes`, starting at a character boundary,
// invalid bytes replaced as in utf8_safe (the tail of a log).
std::string utf8_tail(std::string_view s, size_t max_bytes);

}  // namespace vesper
