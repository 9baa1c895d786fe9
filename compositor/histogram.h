#pragma once
// Luminosity histograms: 256 bins over a display-referred image, or log2
// luminance (stops) over a scene-linear one; statistics, a distance between
// two histograms (Wasserstein-1 on the CDFs), the exposure shift that matches
// a reference's median, JSON, a PNG plot and a terminal rendering.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "compositor/rgba_image.h"

namespace vesper {

enum class LumaWeights { Rec709, Luminosity };  // 0.2126/0.7152/0.0722 or 0.30/0.59/0.11

enum class HistogramDomain { Display, Log2 };

// (r, g, b) coefficients, "rec709" / "luminosity", and the inverse (nullopt if unknown).
std::array<double, 3> luma_coefficients(LumaWeights weights);
const char* luma_weights_name(LumaWeights weights);
std::optional<LumaWeights> parse_luma_weights(std::string_view name);
const char* histogram_domain_name(HistogramDomain domain);  // "display" / "log2"

// Luminance of one pixel, computed as g + wr (r - g) + wb (b - g) so that a
// grey pixel's luminance is exactly its value.
double luminance(float r, float g, float b, LumaWeights weights);

// The sRGB transfer function (IEC 61966-2-1), extended as identity-signed for v <= 0.
double srgb_encode(double linear);
double srgb_decode(double encoded);

struct Histogram {
  HistogramDomain domain = HistogramDomain::Display;
  LumaWeights weights = LumaWeights::Rec709;
  double lo = 0, hi = 1;       // value range of the bins (display: [0,1]; log2: stops)
  std::vector<uint64_t> bins;  // 256
  uint64_t count = 0;          // pixels counted (sum of bins)
  double mean = 0, median = 0;
  std::vector<std::pair<double, double>> percentiles;  // (p, value) for p in 1,5,25,50,75,95,99
  double clipped_low = 0, clipped_high = 0;            // fractions at/below lo and at/above hi
};

// Luminance of the display-referred pixels, 256 bins over [0, 1]; values
// <= 0 land in the first bin and count as clipped_low, values >= 1 in the last
// and count as clipped_high. Statistics come from the exact values (not the
// bins); percentiles interpolate linearly between order statistics.
// NaN counts as 0, +inf as the top of the range.
Histogram display_histogram(const RgbaImage& display_referred, LumaWeights weights);
// log2 of the scene-linear luminance in stops, 256 bins over [lo_stops, hi_stops].
// Luminance <= 0 (no finite stop value) counts as clipped_low and enters the
// statistics as lo_stops; finite stop values outside the range land in the end
// bins, count as clipped, and enter the statistics exactly.
Histogram log2_histogram(const RgbaImage& scene_linear, LumaWeights weights, double lo_stops = -12,
                         double hi_stops = 8);

// Wasserstein-1 distance between two histograms of the same domain and range,
// in the domain's units (display value, or stops).
double wasserstein1(const Histogram& a, const Histogram& b);

// Throws CompError if the domains, ranges or bin counts differ, or a histogram is empty.

// Stops to add to `image`'s exposure so that its median luminance matches the
// reference's (log2 of the ratio of medians, through the domain's transfer).
// Log2 domain: reference.median - image.median. Display domain: the display
// histogram is assumed sRGB-encoded; both medians are decoded with the sRGB
// inverse transfer and the shift is log2(ref_linear / image_linear).
// Throws CompError if the domains differ or a median is black (no finite shift).
double matching_exposure_shift(const Histogram& image, const Histogram& reference);

// {"format": "vesper-histogram/1", "domain", "weights": {"name", "r", "g", "b"},
//  "range": [lo, hi], "bins": [256], "count", "mean", "median",
//  "percentiles": {"1": .., "5", "25", "50", "75", "95", "99"},
//  "clipped": {"low", "high"}} and, with a reference, "reference": {the same},
//  "distance": {"wasserstein1": x}, "matching_exposure_stops": y (null if undefined).
std::string histogram_json(const Histogram& h, const Histogram* reference = nullptr);
nlohmann::json histogram_to_json(const Histogram& h, const Histogram* reference = nullptr);
// An 800x400 RGB plot (PNG, or any format OpenImageIO writes, by extension):
// filled histogram (fractions of the pixel count; the end bins are capped if
// they dwarf the rest), reference outline, quarter gridlines, median markers,
// clipped fractions as red bars at the sides, a value key strip underneath.
// Written atomically (temporary file + rename). Throws CompError.
void write_histogram_png(const Histogram& h, const std::filesystem::path& path,
                         const Histogram* reference = nullptr);
// `height` rows of Unicode blocks over `width` columns (bins merged; 1..256),
// then one line: range, median, mean, clipped fractions.
std::string terminal_histogram(const Histogram& h, int width = 64, int height = 8);

// An image to take a histogram of, read with OpenImageIO. OpenEXR and Radiance
// HDR files are scene-linear; everything else (PNG, JPEG, TIFF, ...) is taken as
// display-referred. RGB from the R,G,B channels (the beauty of a multi-layer
// EXR), a single channel is grey. Throws CompError naming the file.
struct HistogramSource {
  RgbaImage image;
  bool scene_linear = false;
  std::string format;  // OpenImageIO format name ("png", "openexr", ...)
};
HistogramSource read_histogram_source(const std::filesystem::path& path);

}  // namespace vesper
