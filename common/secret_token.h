#pragma once
// Secrets of the farm (bearer tokens, unguessable ids and temp names): random
// bytes from OpenSSL's CSPRNG, and a comparison that does not leak where two
// tokens differ.
#include <string>
#include <string_view>

namespace vesper {

// n random bytes from OpenSSL's CSPRNG, hex encoded (2n characters).
std::string random_hex(int bytes);

// Compares in time that depends only on the lengths, not on where the
// strings differ.
bool constant_time_equal(std::string_view a, std::string_view b);

}  // namespace vesper
