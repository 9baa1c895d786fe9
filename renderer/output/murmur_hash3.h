#pragma once
// MurmurHash3_x86_32 (Austin Appleby's public-domain hash), the hash the
// Cryptomatte specification names for its ids. Hand-written from the
// algorithm's description because no Debian package offers it for C++.
#include <cstdint>
#include <cstring>
#include <string_view>

namespace vesper {

namespace murmur_detail {
inline uint32_t rotl32(uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }
inline uint32_t mix_block(uint32_t k) {
  k *= 0xcc9e2d51u;
  k = rotl32(k, 15);
  return k * 0x1b873593u;
}
inline uint32_t finalize(uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  return h ^ (h >> 16);
}
}  // namespace murmur_detail

// The 32-bit hash of `bytes` (blocks read little-endian, as on x86).
inline uint32_t murmur_hash3_x86_32(std::string_view bytes, uint32_t seed = 0) {
  using namespace murmur_detail;
  const size_t n = bytes.size(), blocks = n / 4;
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  uint32_t h = seed;
  for (size_t i = 0; i < blocks; ++i) {
    const unsigned char* b = p + 4 * i;
    const uint32_t k =
        uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
    h ^= mix_block(k);
    h = rotl32(h, 13);
    h = h * 5 + 0xe6546b64u;
  }
  const unsigned char* tail = p + 4 * blocks;
  uint32_t k = 0;
  switch (n & 3) {
    case 3:
      k ^= uint32_t(tail[2]) << 16;
      [[fallthrough]];
    case 2:
      k ^= uint32_t(tail[1]) << 8;
      [[fallthrough]];
    case 1:
      k ^= uint32_t(tail[0]);
      h ^= mix_block(k);
  }
  h ^= uint32_t(n);
  return finalize(h);
}

}  // namespace vesper
