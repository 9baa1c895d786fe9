#pragma once
// The exact state of a frame's pixels while it is being sampled: per pixel
// and channel the fixed-point sample sums (output/exact_sum.h), per pixel and
// sample stream (sampling/sample_streams.h) the sample counts and, for the
// "streamed" channels whose variance is wanted, their per-stream sums.
// Everything is an integer, so sums over any split of the samples add up to
// the same bits, and the image is formed from them by the one function
// resolve_pixel().
//
// Derived channels: `variance.R/G/B` (the variance of the beauty's pixel
// mean), `<layer>.variance.R/G/B` (the same for a layer's R, G, B) and `spp`
// (samples taken in the pixel) are image channels whose values come from the
// counts and stream sums; their entries in `sums` stay 0.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "renderer/output/exact_sum.h"
#include "renderer/output/layered_image.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper {

inline constexpr char kVarianceLayer[] = "variance";
inline constexpr std::array<const char*, 3> kVarianceChannels{"variance.R", "variance.G",
                                                              "variance.B"};
inline constexpr char kSppChannel[] = "spp";
// Added to the squared mean in the relative error, so that black pixels do
// not need infinitely many samples (relMSE's r² + 0.01).
inline constexpr double kRelativeErrorOffset = 0.01;

// The channel whose variance a derived channel holds ("variance.R" -> "R",
// "fog.variance.G" -> "fog.G"), or "" if `name` is not a variance channel.
std::string variance_source(const std::string& name);
// The variance channel of a channel ("R" -> "variance.R", "fog.G" -> "fog.variance.G").
std::string variance_channel_of(const std::string& channel);
bool is_derived_channel(const std::string& name);

// Pointers to one pixel's state.
struct PixelSums {
  ExactSum* sums = nullptr;         // one per channel
  ExactSum* stream_sums = nullptr;  // [stream][streamed channel]; null when none
  uint32_t* counts = nullptr;       // one per stream
};

struct ConstPixelSums {
  const ExactSum* sums = nullptr;
  const ExactSum* stream_sums = nullptr;
  const uint32_t* counts = nullptr;
  size_t streamed = 0;  // streamed channels per stream
};

// Where the derived channels are among a frame's channels.
struct DerivedChannels {
  std::vector<std::pair<int, int>> variance;  // (output channel, streamed channel index)
  int spp = -1;
  bool empty() const { return variance.empty() && spp < 0; }
};
// Throws std::invalid_argument if a variance channel's source is not streamed.
DerivedChannels find_derived_channels(const std::vector<std::string>& channels,
                                      const std::vector<int>& streamed);

struct FilmSums {
  int width = 0, height = 0;
  std::vector<std::string> channels;  // the image's channels
  // The channels whose per-stream sums are kept, for their variance; when
  // the beauty is among them (adaptive sampling), R, G, B are the first three.
  std::vector<int> streamed;
  std::vector<ExactSum> sums;         // (pixel * channels + c)
  std::vector<ExactSum> stream_sums;  // (pixel * K + stream) * streamed + j
  std::vector<uint32_t> counts;       // pixel * K + stream

  FilmSums() = default;
  FilmSums(int width, int height, std::vector<std::string> channels, std::vector<int> streamed);
  size_t pixel_count() const { return size_t(width) * size_t(height); }
  bool has_variance() const { return !streamed.empty(); }
  PixelSums pixel(size_t p);
  ConstPixelSums pixel(size_t p) const;
  // Adds another film of the same frame (same size and channels), exactly.
  void add(const FilmSums& other);
  // Appends `keep` channels of a film of the same frame (a variant layer's
  // render: same size and counts), with their stream sums where streamed.
  void append_channels(const FilmSums& other, const std::vector<size_t>& keep);
};

// Samples taken in a pixel (over all streams).
int64_t sample_count(const uint32_t* counts);

// Variance of the pixel mean of streamed channel j: the streams' sums S_k
// over n_k samples are independent, each modelled with variance n_k τ²; τ²
// is estimated from their spread about the pixel mean and var(mean) = τ²/n.
// With equal n_k this is the textbook variance of the mean of K independent
// stream means. 0 with fewer than two non-empty streams.
double pixel_variance(ConstPixelSums px, size_t j);

// The pixel's estimated relative error of the mean, in relMSE's own terms
// (DESIGN.md): sqrt of the mean over R, G, B of var(mean) / (mean² + 0.01),
// so that the RMS of it over an image estimates sqrt(relMSE). (The form
// sqrt(var) / (|mean| + 0.01), max over R, G, B, weighs a dark pixel up to
// 100x more than relMSE does and spent the samples there.) R, G, B must be the first streamed
// channels.
double pixel_relative_error(ConstPixelSums px);

// Writes the pixel's image values (means of the summed channels, derived
// channels from counts and stream sums) to out[0 .. channels).
void resolve_pixel(ConstPixelSums px, size_t channels, const DerivedChannels& derived, float* out);

// The whole image (pixels only; metadata is the caller's).
LayeredImage resolve_image(const FilmSums& film);

// Summary figures of a film, for the metadata.
struct NoiseSummary {
  double rms_relative_error = 0;  // sqrt(mean over pixels of pixel_relative_error²)
  double mean_spp = 0;
  int64_t min_spp = 0, max_spp = 0;
};
NoiseSummary summarize_noise(const FilmSums& film);

// vesper:spp_mean and (when the beauty is streamed) vesper:noise_reached.
void set_noise_metadata(std::map<std::string, std::string>& metadata, const FilmSums& film);

// Whether the film streams the beauty's R, G, B (its first three channels).
bool streams_beauty(const FilmSums& film);

}  // namespace vesper
