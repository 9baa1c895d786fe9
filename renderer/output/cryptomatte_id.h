#pragma once
// Cryptomatte ids (Psyop's specification, Friedman & Jones 2015): a name's
// MurmurHash3_x86_32 (seed 0) of its UTF-8 bytes, stored as the float with
// the same bits, except that an exponent of 0 (zero or denormal) or 255
// (inf/NaN) has its lowest bit (bit 23) flipped, to 1 or 254, so that every
// id is a normal finite float. (The 1.1 text clamps the exponent to
// [1, 254]; the reference code flips bit 23: the same result.)
#include <bit>
#include <cstdint>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "renderer/output/murmur_hash3.h"

namespace vesper {

// The id's bits (what the manifest writes in hex) from a name's hash.
inline uint32_t crypto_id_bits_of_hash(uint32_t hash) {
  const uint32_t exponent = (hash >> 23) & 0xffu;
  return exponent == 0 || exponent == 255 ? hash ^ (1u << 23) : hash;
}
inline uint32_t crypto_id_bits(std::string_view name) {
  return crypto_id_bits_of_hash(murmur_hash3_x86_32(name));
}
// The id as the pixels hold it.
inline float crypto_id(std::string_view name) { return std::bit_cast<float>(crypto_id_bits(name)); }

// 8 lowercase hex digits, as in the manifest ("13851a76").
inline std::string crypto_hex(uint32_t bits) { return fmt::format("{:08x}", bits); }

// The metadata key of a Cryptomatte type ("CryptoObject"): the first 7 hex
// digits of its name's id, as the reference implementation derives it
// (layer_hash in Psyop's cryptomatte_utilities.py), so that it is the same
// in every frame and shot.
inline std::string crypto_metadata_key(std::string_view type_name) {
  return crypto_hex(crypto_id_bits(type_name)).substr(0, 7);
}

}  // namespace vesper
