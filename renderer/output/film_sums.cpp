#include "renderer/output/film_sums.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/output/metadata_keys.h"

namespace vesper {
namespace {

constexpr size_t kStreams = size_t(kSampleStreams);

// The R, G, B stream sums of a pixel summed over the streams, as doubles.
double stream_total(ConstPixelSums px, int c) {
  ExactSum s = 0;
  for (size_t k = 0; k < kStreams; ++k) s += px.stream_sums[k * 3 + size_t(c)];
  return fixed_to_double(s);
}

}  // namespace

bool is_derived_channel(const std::string& name) {
  return name == kSppChannel ||
         std::find_if(kVarianceChannels.begin(), kVarianceChannels.end(),
                      [&](const char* v) { return name == v; }) != kVarianceChannels.end();
}

DerivedChannels find_derived_channels(const std::vector<std::string>& channels) {
  DerivedChannels d;
  for (size_t c = 0; c < channels.size(); ++c) {
    if (channels[c] == kVarianceChannels[0]) d.variance = int(c);
    if (channels[c] == kSppChannel) d.spp = int(c);
  }
  return d;
}

FilmSums::FilmSums(int w, int h, std::vector<std::string> names, bool variance)
    : width(w), height(h), channels(std::move(names)), has_variance(variance) {
  sums.assign(pixel_count() * channels.size(), 0);
  counts.assign(pixel_count() * kStreams, 0);
  if (variance) stream_sums.assign(pixel_count() * kStreams * 3, 0);
}

PixelSums FilmSums::pixel(size_t p) {
  return {sums.data() + p * channels.size(),
          has_variance ? stream_sums.data() + p * kStreams * 3 : nullptr,
          counts.data() + p * kStreams};
}

ConstPixelSums FilmSums::pixel(size_t p) const {
  return {sums.data() + p * channels.size(),
          has_variance ? stream_sums.data() + p * kStreams * 3 : nullptr,
          counts.data() + p * kStreams};
}

void FilmSums::add(const FilmSums& o) {
  if (o.width != width || o.height != height || o.channels != channels ||
      o.has_variance != has_variance)
    throw std::invalid_argument("FilmSums::add: films of different frames");
  for (size_t i = 0; i < sums.size(); ++i) sums[i] += o.sums[i];
  for (size_t i = 0; i < stream_sums.size(); ++i) stream_sums[i] += o.stream_sums[i];
  for (size_t i = 0; i < counts.size(); ++i) counts[i] += o.counts[i];
}

int64_t sample_count(const uint32_t* counts) {
  int64_t n = 0;
  for (size_t k = 0; k < kStreams; ++k) n += counts[k];
  return n;
}

double pixel_variance(ConstPixelSums px, int c) {
  const int64_t n = sample_count(px.counts);
  int streams = 0;
  for (size_t k = 0; k < kStreams; ++k) streams += px.counts[k] > 0;
  if (streams < 2) return 0;
  const double mean = stream_total(px, c) / double(n);
  double spread = 0;
  for (size_t k = 0; k < kStreams; ++k) {
    if (px.counts[k] == 0) continue;
    const double nk = double(px.counts[k]);
    const double d = fixed_to_double(px.stream_sums[k * 3 + size_t(c)]) - nk * mean;
    spread += d * d / nk;
  }
  return spread / double(streams - 1) / double(n);
}

double pixel_relative_error(ConstPixelSums px) {
  const int64_t n = sample_count(px.counts);
  if (n == 0) return INFINITY;
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    const double mean = stream_total(px, c) / double(n);
    worst =
        std::max(worst, std::sqrt(pixel_variance(px, c)) / (std::abs(mean) + kRelativeErrorOffset));
  }
  return worst;
}

void resolve_pixel(ConstPixelSums px, size_t channels, const DerivedChannels& derived, float* out) {
  const int64_t n = sample_count(px.counts);
  for (size_t c = 0; c < channels; ++c) out[c] = exact_mean(px.sums[c], n);
  if (derived.variance >= 0)
    for (int c = 0; c < 3; ++c)
      out[derived.variance + c] = px.stream_sums ? float(pixel_variance(px, c)) : 0.f;
  if (derived.spp >= 0) out[derived.spp] = float(n);
}

LayeredImage resolve_image(const FilmSums& film) {
  LayeredImage img;
  img.width = film.width;
  img.height = film.height;
  img.channels = film.channels;
  img.pixels.resize(film.sums.size());
  const DerivedChannels derived = find_derived_channels(film.channels);
  const size_t nc = film.channels.size();
  for (size_t p = 0; p < film.pixel_count(); ++p)
    resolve_pixel(film.pixel(p), nc, derived, img.pixels.data() + p * nc);
  return img;
}

NoiseSummary summarize_noise(const FilmSums& film) {
  NoiseSummary s;
  const size_t pixels = film.pixel_count();
  if (pixels == 0) return s;
  double sum_sq = 0, sum_spp = 0;
  s.min_spp = INT64_MAX;
  for (size_t p = 0; p < pixels; ++p) {
    const ConstPixelSums px = film.pixel(p);
    const int64_t n = sample_count(px.counts);
    sum_spp += double(n);
    s.min_spp = std::min(s.min_spp, n);
    s.max_spp = std::max(s.max_spp, n);
    if (film.has_variance) {
      const double e = pixel_relative_error(px);
      sum_sq += std::isfinite(e) ? e * e : 0;
    }
  }
  s.mean_spp = sum_spp / double(pixels);
  s.rms_relative_error = std::sqrt(sum_sq / double(pixels));
  return s;
}

void set_noise_metadata(std::map<std::string, std::string>& metadata, const FilmSums& film) {
  const NoiseSummary s = summarize_noise(film);
  metadata[metadata_key::kSppMean] = std::to_string(s.mean_spp);
  if (film.has_variance)
    metadata[metadata_key::kNoiseReached] = std::to_string(s.rms_relative_error);
}

}  // namespace vesper
