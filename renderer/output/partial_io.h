#pragma once
// Partial renders: the exact per-pixel sample sums of one sample range of a
// frame (docs/partial-format.md), and their merge into the image a single
// render of the union of the ranges gives, bit for bit.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/output/crypto_film.h"
#include "renderer/output/exact_sum.h"
#include "renderer/output/film_sums.h"
#include "renderer/output/layered_image.h"

namespace vesper {

struct PartialError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Partial {
  std::string source;  // the file it was read from (or a label): named in errors
  int width = 0, height = 0;
  std::vector<std::string> channels;  // as the image's (EXR) channels
  int sample_begin = 0, sample_end = 0;
  int frame_spp = 0;  // samples per pixel of the whole frame
  uint64_t seed = 0;
  std::string scene_hash, renderer_version;
  uint64_t nonfinite_samples = 0;  // NaN/Inf samples dropped in this range
  double render_seconds = 0;
  // Every other metadata key of the frame (vesper:passes, vesper:frame, ...):
  // must be equal in all partials of a frame, and is copied to the merged image.
  std::map<std::string, std::string> metadata;
  // Fixed-point sums, (y * width + x) * channels.size() + c.
  std::vector<ExactSum> sums;
  // The channels whose per-stream sums are kept (film_sums.h: for their
  // variance), their sums per pixel and stream, and the per-pixel, per-stream
  // sample counts.
  std::vector<int> streamed;
  std::vector<ExactSum> stream_sums;
  std::vector<uint32_t> counts;
  // With the cryptomatte AOV: per pixel, the samples and their counts by id,
  // unranked (the Crypto channels are not among `channels`: a merge forms them).
  std::optional<CryptoFilm> crypto;

  FilmSums film() const;  // the sums as a film (copies)
};

// A partial from a frame rendered with RenderOptions::keep_sums (the image's
// metadata gives the range, seed, scene hash, ...; `crypto` is the render's
// Cryptomatte film, whose channels the image holds). Throws PartialError if
// the metadata lacks a key render() writes or the sums do not match the image.
Partial make_partial(const LayeredImage& image, FilmSums film, int frame_spp,
                     std::string source = "render", std::optional<CryptoFilm> crypto = {});

// Writes atomically (temporary file beside `path`, then rename).
void write_partial(const Partial& partial, const std::filesystem::path& path);

// Reads and validates everything; a PartialError names the file and what is wrong.
Partial read_partial(const std::filesystem::path& path);

// The frame of the union of the partials' sample ranges, bitwise identical to
// a single render of that range: same channels, pixels resolved from the
// summed film (resolve_image: exact_mean(sum of sums, sum of counts), the
// variance from the summed stream sums), metadata as render() writes it (spp,
// sample_begin/end of the union; render_seconds and nonfinite_samples summed;
// noise reached and mean spp recomputed).
// Throws PartialError (naming the partials' sources) unless the partials are
// of one frame (size, channels, seed, scene hash, renderer version, frame spp,
// other metadata) and their ranges tile one contiguous range without overlap.
LayeredImage merge_partials(const std::vector<Partial>& partials);

}  // namespace vesper
