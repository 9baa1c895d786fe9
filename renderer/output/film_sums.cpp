#include "renderer/output/film_sums.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/output/metadata_keys.h"
#include "renderer/output/metadata_text.h"

namespace vesper {
namespace {

constexpr size_t kStreams = size_t(kSampleStreams);
constexpr char kVarianceSegment[] = "variance.";

// Sum over the streams of streamed channel j, as a double.
double stream_total(ConstPixelSums px, size_t j) {
  ExactSum s = 0;
  for (size_t k = 0; k < kStreams; ++k) s += px.stream_sums[k * px.streamed + j];
  return fixed_to_double(s);
}

}  // namespace

std::string variance_source(const std::string& name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos) return "";
  const std::string prefix = name.substr(0, dot + 1), channel = name.substr(dot + 1);
  const std::string segment = kVarianceSegment;
  if (prefix == segment) return channel;
  if (prefix.size() > segment.size() && prefix.ends_with("." + segment))
    return prefix.substr(0, prefix.size() - segment.size()) + channel;
  return "";
}

std::string variance_channel_of(const std::string& channel) {
  const size_t dot = channel.rfind('.');
  if (dot == std::string::npos) return kVarianceSegment + channel;
  return channel.substr(0, dot + 1) + kVarianceSegment + channel.substr(dot + 1);
}

bool is_derived_channel(const std::string& name) {
  return name == kSppChannel || !variance_source(name).empty();
}

DerivedChannels find_derived_channels(const std::vector<std::string>& channels,
                                      const std::vector<int>& streamed) {
  DerivedChannels d;
  for (size_t c = 0; c < channels.size(); ++c) {
    if (channels[c] == kSppChannel) d.spp = int(c);
    const std::string source = variance_source(channels[c]);
    if (source.empty()) continue;
    const auto it = std::find_if(streamed.begin(), streamed.end(),
                                 [&](int s) { return channels[size_t(s)] == source; });
    if (it == streamed.end())
      throw std::invalid_argument("channel " + channels[c] + ": no stream sums of " + source +
                                  " to estimate its variance from");
    d.variance.emplace_back(int(c), int(it - streamed.begin()));
  }
  return d;
}

FilmSums::FilmSums(int w, int h, std::vector<std::string> names, std::vector<int> streamed_channels)
    : width(w), height(h), channels(std::move(names)), streamed(std::move(streamed_channels)) {
  sums.assign(pixel_count() * channels.size(), 0);
  counts.assign(pixel_count() * kStreams, 0);
  stream_sums.assign(pixel_count() * kStreams * streamed.size(), 0);
}

PixelSums FilmSums::pixel(size_t p) {
  return {sums.data() + p * channels.size(),
          streamed.empty() ? nullptr : stream_sums.data() + p * kStreams * streamed.size(),
          counts.data() + p * kStreams};
}

ConstPixelSums FilmSums::pixel(size_t p) const {
  return {sums.data() + p * channels.size(),
          streamed.empty() ? nullptr : stream_sums.data() + p * kStreams * streamed.size(),
          counts.data() + p * kStreams, streamed.size()};
}

void FilmSums::add(const FilmSums& o) {
  if (o.width != width || o.height != height || o.channels != channels || o.streamed != streamed)
    throw std::invalid_argument("FilmSums::add: films of different frames");
  for (size_t i = 0; i < sums.size(); ++i) sums[i] += o.sums[i];
  for (size_t i = 0; i < stream_sums.size(); ++i) stream_sums[i] += o.stream_sums[i];
  for (size_t i = 0; i < counts.size(); ++i) counts[i] += o.counts[i];
}

void FilmSums::append_channels(const FilmSums& o, const std::vector<size_t>& keep) {
  const size_t nc = channels.size(), ns = streamed.size();
  std::vector<int> new_streamed = streamed;
  std::vector<size_t> keep_streamed;  // indices into o.streamed
  for (size_t k = 0; k < keep.size(); ++k)
    for (size_t j = 0; j < o.streamed.size(); ++j)
      if (size_t(o.streamed[j]) == keep[k]) {
        new_streamed.push_back(int(nc + k));
        keep_streamed.push_back(j);
      }
  const size_t pixels = pixel_count(), mc = nc + keep.size(), ms = new_streamed.size();
  std::vector<ExactSum> merged(pixels * mc), merged_streams(pixels * kStreams * ms);
  for (size_t p = 0; p < pixels; ++p) {
    std::copy_n(&sums[p * nc], nc, &merged[p * mc]);
    for (size_t k = 0; k < keep.size(); ++k)
      merged[p * mc + nc + k] = o.sums[p * o.channels.size() + keep[k]];
    for (size_t s = 0; s < kStreams; ++s) {
      const size_t row = p * kStreams + s;
      std::copy_n(&stream_sums[row * ns], ns, &merged_streams[row * ms]);
      for (size_t k = 0; k < keep_streamed.size(); ++k)
        merged_streams[row * ms + ns + k] =
            o.stream_sums[row * o.streamed.size() + keep_streamed[k]];
    }
  }
  for (size_t k : keep) channels.push_back(o.channels[k]);
  sums = std::move(merged);
  stream_sums = std::move(merged_streams);
  streamed = std::move(new_streamed);
}

int64_t sample_count(const uint32_t* counts) {
  int64_t n = 0;
  for (size_t k = 0; k < kStreams; ++k) n += counts[k];
  return n;
}

double pixel_variance(ConstPixelSums px, size_t j) {
  const int64_t n = sample_count(px.counts);
  int streams = 0;
  for (size_t k = 0; k < kStreams; ++k) streams += px.counts[k] > 0;
  if (streams < 2) return 0;
  const double mean = stream_total(px, j) / double(n);
  double spread = 0;
  for (size_t k = 0; k < kStreams; ++k) {
    if (px.counts[k] == 0) continue;
    const double nk = double(px.counts[k]);
    const double d = fixed_to_double(px.stream_sums[k * px.streamed + j]) - nk * mean;
    spread += d * d / nk;
  }
  return spread / double(streams - 1) / double(n);
}

double pixel_relative_error(ConstPixelSums px) {
  const int64_t n = sample_count(px.counts);
  if (n == 0) return INFINITY;
  double sum = 0;
  for (size_t c = 0; c < 3; ++c) {
    const double mean = stream_total(px, c) / double(n);
    sum += pixel_variance(px, c) / (mean * mean + kRelativeErrorOffset);
  }
  return std::sqrt(sum / 3);
}

void resolve_pixel(ConstPixelSums px, size_t channels, const DerivedChannels& derived, float* out) {
  const int64_t n = sample_count(px.counts);
  for (size_t c = 0; c < channels; ++c) out[c] = exact_mean(px.sums[c], n);
  for (const auto& [channel, j] : derived.variance)
    out[channel] = float(pixel_variance(px, size_t(j)));
  if (derived.spp >= 0) out[derived.spp] = float(n);
}

LayeredImage resolve_image(const FilmSums& film) {
  LayeredImage img;
  img.width = film.width;
  img.height = film.height;
  img.channels = film.channels;
  img.pixels.resize(film.sums.size());
  const DerivedChannels derived = find_derived_channels(film.channels, film.streamed);
  const size_t nc = film.channels.size();
  for (size_t p = 0; p < film.pixel_count(); ++p)
    resolve_pixel(film.pixel(p), nc, derived, img.pixels.data() + p * nc);
  return img;
}

bool streams_beauty(const FilmSums& film) {
  return film.streamed.size() >= 3 && film.streamed[0] == 0 && film.streamed[1] == 1 &&
         film.streamed[2] == 2;
}

NoiseSummary summarize_noise(const FilmSums& film) {
  NoiseSummary s;
  const size_t pixels = film.pixel_count();
  if (pixels == 0) return s;
  const bool beauty = streams_beauty(film);
  double sum_sq = 0, sum_spp = 0;
  s.min_spp = INT64_MAX;
  for (size_t p = 0; p < pixels; ++p) {
    const ConstPixelSums px = film.pixel(p);
    const int64_t n = sample_count(px.counts);
    sum_spp += double(n);
    s.min_spp = std::min(s.min_spp, n);
    s.max_spp = std::max(s.max_spp, n);
    if (beauty) {
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
  metadata[metadata_key::kSppMean] = metadata_number(s.mean_spp);
  if (streams_beauty(film))
    metadata[metadata_key::kNoiseReached] = metadata_number(s.rms_relative_error);
}

}  // namespace vesper
