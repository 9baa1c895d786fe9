#pragma once
// Cryptomatte id mattes (Psyop's specification, Friedman & Jones 2015):
// per pixel, the share of its camera samples whose first surface (the camera
// ray's first hit; media ignored) is each shape, written as ranked
// (id, coverage) pairs twice: by object (shape names) and by material.
// Samples are drawn from the pixel filter and weigh the same, so a plain
// count is the filter-weighted coverage. Counts are integers added in each
// pixel by the one thread that samples it: any thread count gives the same
// image. Internal to render/.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "renderer/output/crypto_film.h"
#include "renderer/output/layered_image.h"
#include "renderer/scene/scene.h"

namespace vesper {

// Ranks per type when not told otherwise: the specification's suggested
// default, 3 RGBA layers (CryptoObject00, 01, 02).
inline constexpr int kCryptoDefaultDepth = 6;
inline constexpr char kCryptoObject[] = "CryptoObject";
inline constexpr char kCryptoMaterial[] = "CryptoMaterial";

// Per pixel: how many camera samples first hit each shape, and how many were taken.
class CryptoCounts {
 public:
  struct Entry {
    uint32_t shape = 0, count = 0;
  };
  explicit CryptoCounts(size_t pixels) : shapes_(pixels), totals_(pixels, 0) {}
  // One camera sample of `pixel` whose first hit is `shape` (-1: none, the background).
  void add(size_t pixel, int32_t shape) {
    ++totals_[pixel];
    if (shape < 0) return;
    for (Entry& e : shapes_[pixel])
      if (e.shape == uint32_t(shape)) {
        ++e.count;
        return;
      }
    shapes_[pixel].push_back({uint32_t(shape), 1});
  }
  const std::vector<Entry>& shapes(size_t pixel) const { return shapes_[pixel]; }
  uint32_t total(size_t pixel) const { return totals_[pixel]; }

 private:
  std::vector<std::vector<Entry>> shapes_;
  std::vector<uint32_t> totals_;
};

// Appends CryptoObject00.R/G/B/A ... and CryptoMaterial00.R/G/B/A ...
// ((depth + 1) / 2 layers each: id rank 2k, its coverage, id rank 2k+1, its
// coverage) and their header attributes cryptomatte/<key>/name, hash,
// conversion, manifest to `image`. Returns the unranked counts by id, which a
// partial render carries so that a merge ranks them as this render did.
CryptoFilm append_cryptomatte(LayeredImage& image, const Scene& scene, const CryptoCounts& counts,
                              int depth = kCryptoDefaultDepth);

}  // namespace vesper
