#pragma once
// Luminosity histograms: 256 bins over a display-referred image, or log2
// luminance (stops) over a scene-linear one; statistics, a distance between
// two histograms (Wasserstein-1 on the CDFs), the exposure shift that matches
// a reference's median, JSON, a PNG plot and a terminal rendering.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "compositor/rgba_image.h"

namespace vesper {

enum class LumaWeights { Rec709, Luminosity };  // 0.2126/0.7152/0.0722 or 0.30/0.59/0.11

enum class HistogramDomain { Display, Log2 };

struct Histogram {
  HistogramDomain domain = HistogramDomain::Display;
  LumaWeights weights = LumaWeights::Rec709;
  double lo = 0, hi = 1;  // value range of the bins (display: [0,1]; log2: stops)
  std::vector<uint64_t> bins;  // 256
  uint64_t count = 0;          // pixels counted (sum of bins)
  double mean = 0, median = 0;
  std::vector<std::pair<double, double>> percentiles;  // (p, value) for p in 1,5,25,50,75,95,99
  double clipped_low = 0, clipped_high = 0;  // fractions at/below lo and at/above hi
};

Histogram display_histogram(const RgbaImage& display_referred, LumaWeights weights);
Histogram log2_histogram(const RgbaImage& scene_linear, LumaWeights weights, double lo_stops = -12,
                         double hi_stops = 8);

// Wasserstein-1 distance between two histograms of the same domain and range,
// in the domain's units (display value, or stops).
double wasserstein1(const Histogram& a, const Histogram& b);

// Stops to add to `image`'s exposure so that its median luminance matches the
// reference's (log2 of the ratio of medians, through the domain's transfer).
double matching_exposure_shift(const Histogram& image, const Histogram& reference);

std::string histogram_json(const Histogram& h, const Histogram* reference = nullptr);
void write_histogram_png(const Histogram& h, const std::filesystem::path& path, const Histogram* reference = nullptr);
std::string terminal_histogram(const Histogram& h, int width = 64, int height = 8);

}  // namespace vesper
