#pragma once
// The exact state of a frame's pixels while it is being sampled: per pixel
// and channel the fixed-point sample sums (output/exact_sum.h), per pixel and
// sample stream (sampling/sample_streams.h) the sample counts and, when the
// variance is wanted, the stream sums of the beauty R, G, B. Everything is an
// integer, so sums over any split of the samples add up to the same bits, and
// the image is formed from them by the one function resolve_pixel().
//
// Derived channels: `variance.R/G/B` (the variance of the pixel mean, from
// the spread of the stream means) and `spp` (samples taken in the pixel) are
// image channels whose values come from the counts and stream sums; their
// entries in `sums` stay 0.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "renderer/output/exact_sum.h"
#include "renderer/output/layered_image.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper {

inline constexpr char kVarianceLayer[] = "variance";
inline constexpr std::array<const char*, 3> kVarianceChannels{"variance.R", "variance.G",
                                                              "variance.B"};
inline constexpr char kSppChannel[] = "spp";
// Added to the mean in the relative error, so that black pixels do not need
// infinitely many samples (the same 0.01 as relMSE's r² + 0.01).
inline constexpr double kRelativeErrorOffset = 0.01;

// Pointers to one pixel's state; stream_sums is null when no variance is kept.
struct PixelSums {
  ExactSum* sums = nullptr;         // one per channel
  ExactSum* stream_sums = nullptr;  // [stream][R,G,B]
  uint32_t* counts = nullptr;       // one per stream
};

struct ConstPixelSums {
  const ExactSum* sums = nullptr;
  const ExactSum* stream_sums = nullptr;
  const uint32_t* counts = nullptr;
};

// Where the derived channels and the beauty are among a frame's channels.
struct DerivedChannels {
  int variance = -1;  // first of variance.R, G, B, or -1
  int spp = -1;
  bool empty() const { return variance < 0 && spp < 0; }
};
DerivedChannels find_derived_channels(const std::vector<std::string>& channels);
bool is_derived_channel(const std::string& name);

struct FilmSums {
  int width = 0, height = 0;
  std::vector<std::string> channels;  // the image's channels; R, G, B first
  bool has_variance = false;          // stream_sums kept
  std::vector<ExactSum> sums;         // (pixel * channels + c)
  std::vector<ExactSum> stream_sums;  // (pixel * K + stream) * 3 + rgb
  std::vector<uint32_t> counts;       // pixel * K + stream

  FilmSums() = default;
  FilmSums(int width, int height, std::vector<std::string> channels, bool variance);
  size_t pixel_count() const { return size_t(width) * size_t(height); }
  PixelSums pixel(size_t p);
  ConstPixelSums pixel(size_t p) const;
  // Adds another film of the same frame (same size and channels), exactly.
  void add(const FilmSums& other);
};

// Samples taken in a pixel (over all streams).
int64_t sample_count(const uint32_t* counts);

// Variance of the pixel mean of beauty channel c (0..2): the streams'
// sums S_k over n_k samples are independent, each modelled with variance
// n_k τ²; τ² is estimated from their spread about the pixel mean and
// var(mean) = τ² / n. With equal n_k this is the textbook variance of the
// mean of K independent stream means. 0 with fewer than two non-empty streams.
double pixel_variance(ConstPixelSums px, int c);

// The pixel's estimated relative error of the mean: max over R, G, B of
// sqrt(var(mean)) / (|mean| + 0.01). Needs stream sums.
double pixel_relative_error(ConstPixelSums px);

// Writes the pixel's image values (means of the summed channels, derived
// channels from counts and stream sums) to out[0 .. channels).
void resolve_pixel(ConstPixelSums px, size_t channels, const DerivedChannels& derived, float* out);

// The whole image (pixels only; metadata is the caller's).
LayeredImage resolve_image(const FilmSums& film);

// Summary figures of a film with stream sums, for the metadata.
struct NoiseSummary {
  double rms_relative_error = 0;  // sqrt(mean over pixels of pixel_relative_error²)
  double mean_spp = 0;
  int64_t min_spp = 0, max_spp = 0;
};
NoiseSummary summarize_noise(const FilmSums& film);

// vesper:spp_mean and (with stream sums) vesper:noise_reached of the film.
void set_noise_metadata(std::map<std::string, std::string>& metadata, const FilmSums& film);

}  // namespace vesper
