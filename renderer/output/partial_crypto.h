#pragma once
// The optional Cryptomatte section of a partial render (docs/partial-format.md,
// "Cryptomatte"): the header's "cryptomatte" object and the per-pixel id
// counts that follow the sample counts in the body. Internal to output/.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/json_reader.h"
#include "renderer/output/crypto_film.h"
#include "renderer/output/partial_io.h"

namespace vesper::partial_crypto {

// The section's encoded body: per pixel the total (uint32 LE), then per type
// the number of ids n (uint32 LE) and n pairs (id bits, count), uint32 LE each.
std::vector<unsigned char> encode(const CryptoFilm& film);

// The header's "cryptomatte" object for a body of `bytes` bytes.
nlohmann::json header(const CryptoFilm& film, size_t bytes);

// Parses the header object: the film's depth, types and position (no counts
// yet) and the section's byte count. Throws JsonError naming the key.
CryptoFilm parse_header(JsonReader node, const Partial& p, uint64_t& bytes);

// Decodes the section into `film` (sized for p's pixels); a PartialError names
// p.source when the bytes are not a valid section of exactly `size` bytes.
void decode(const unsigned char* data, size_t size, const Partial& p, CryptoFilm& film);

// The film fits the partial: one total and types.size() id lists per pixel,
// position within the channels, no Crypto channel among them.
void check(const Partial& p);

}  // namespace vesper::partial_crypto
