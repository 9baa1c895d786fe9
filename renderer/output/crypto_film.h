#pragma once
// A frame's Cryptomatte state before ranking: per pixel, the camera samples
// taken and, per type (CryptoObject, CryptoMaterial), how many of them first
// hit each id. Counts are integers, so the films of disjoint sample ranges
// add up to the film of their union, and the ranked channels are formed from
// it by the one function append_crypto_channels() (a single render and a
// merge of partials alike; docs/partial-format.md).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "renderer/output/layered_image.h"

namespace vesper {

// (id bits, sample count) pairs of one pixel.
using CryptoIdCounts = std::vector<std::pair<uint32_t, uint32_t>>;

// The `depth` pairs of largest count, by count descending, ties by id bits
// ascending (a fixed order, whatever order the ids arrived in).
CryptoIdCounts rank_crypto_ids(CryptoIdCounts counts, int depth);

struct CryptoFilm {
  int depth = 0;                    // ranks per type
  std::vector<std::string> types;   // "CryptoObject", "CryptoMaterial"
  size_t position = 0;              // image channels before the first Crypto channel
  std::vector<uint32_t> totals;     // per pixel: camera samples taken
  std::vector<CryptoIdCounts> ids;  // pixel * types.size() + type; one pair per id, any order

  size_t pixels() const { return totals.size(); }
  // Adds another range's counts (same depth, types, position and size).
  void add(const CryptoFilm& other);
};

// The channel names of one type: <type>00.R/G/B/A ... ((depth + 1) / 2 layers:
// id rank 2k, its coverage, id rank 2k+1, its coverage).
std::vector<std::string> crypto_channel_names(const std::string& type, int depth);
// Every type's channel names, in image order.
std::vector<std::string> crypto_channel_names(const CryptoFilm& film);

// Inserts the ranked id/coverage channels of every type at film.position of
// `image` (coverage = count / total, in double, rounded once to float).
void append_crypto_channels(LayeredImage& image, const CryptoFilm& film);

}  // namespace vesper
