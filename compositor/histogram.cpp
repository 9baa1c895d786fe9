// Luminosity histograms: statistics, distance, exposure matching, JSON, the
// terminal rendering and reading an image to measure. The PNG plot is in
// histogram_plot.cpp.
#include "compositor/histogram.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace vesper {

namespace {

constexpr int kBins = 256;
constexpr double kPercentiles[] = {1, 5, 25, 50, 75, 95, 99};

// Linear interpolation between order statistics (numpy's default, "type 7").
double percentile_sorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double pos = p / 100.0 * double(sorted.size() - 1);
  const size_t i = size_t(std::floor(pos));
  const double f = pos - double(i);
  if (i + 1 >= sorted.size()) return sorted.back();
  return sorted[i] + f * (sorted[i + 1] - sorted[i]);
}

// Bins, clipping (at/below lo, at/above hi) and statistics of `values` over
// [lo, hi]; sorts `values`.
Histogram build(std::vector<double>& values, HistogramDomain domain, LumaWeights weights, double lo,
                double hi) {
  Histogram h;
  h.domain = domain;
  h.weights = weights;
  h.lo = lo;
  h.hi = hi;
  h.bins.assign(kBins, 0);
  h.count = values.size();
  if (values.empty()) return h;
  const double scale = double(kBins) / (hi - lo);
  uint64_t low = 0, high = 0;
  double sum = 0;
  for (const double v : values) {
    if (v <= lo) ++low;
    if (v >= hi) ++high;
    const double b = std::floor((v - lo) * scale);
    const int bin = b < 0 ? 0 : b >= kBins ? kBins - 1 : int(b);
    ++h.bins[size_t(bin)];
    sum += v;
  }
  const double n = double(values.size());
  h.mean = sum / n;
  h.clipped_low = double(low) / n;
  h.clipped_high = double(high) / n;
  std::sort(values.begin(), values.end());
  for (const double p : kPercentiles) h.percentiles.emplace_back(p, percentile_sorted(values, p));
  h.median = percentile_sorted(values, 50);
  return h;
}

void require_comparable(const Histogram& a, const Histogram& b, const char* what) {
  if (a.domain != b.domain)
    throw CompError(fmt::format("{}: histograms of different domains ({} vs {})", what,
                                histogram_domain_name(a.domain), histogram_domain_name(b.domain)));
  if (a.lo != b.lo || a.hi != b.hi || a.bins.size() != b.bins.size())
    throw CompError(
        fmt::format("{}: histograms of different ranges ([{:g}, {:g}] x {} vs [{:g}, {:g}] x {})",
                    what, a.lo, a.hi, a.bins.size(), b.lo, b.hi, b.bins.size()));
  if (a.count == 0 || b.count == 0) throw CompError(fmt::format("{}: empty histogram", what));
}

std::string pct(double fraction) {
  const double p = fraction * 100.0;
  if (p == 0) return "0%";
  if (p < 0.1) return "<0.1%";
  return fmt::format("{:.1f}%", p);
}

}  // namespace

std::array<double, 3> luma_coefficients(LumaWeights w) {
  switch (w) {
    case LumaWeights::Luminosity:
      return {0.30, 0.59, 0.11};
    case LumaWeights::Rec709:
      break;
  }
  return {0.2126, 0.7152, 0.0722};
}

const char* luma_weights_name(LumaWeights w) {
  return w == LumaWeights::Luminosity ? "luminosity" : "rec709";
}

std::optional<LumaWeights> parse_luma_weights(std::string_view name) {
  if (name == "rec709") return LumaWeights::Rec709;
  if (name == "luminosity") return LumaWeights::Luminosity;
  return std::nullopt;
}

const char* histogram_domain_name(HistogramDomain d) {
  return d == HistogramDomain::Log2 ? "log2" : "display";
}

double luminance(float r, float g, float b, LumaWeights weights) {
  const auto w = luma_coefficients(weights);
  return double(g) + w[0] * (double(r) - double(g)) + w[2] * (double(b) - double(g));
}

double srgb_encode(double v) {
  if (v <= 0.0031308) return 12.92 * v;
  return 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double v) {
  if (v <= 0.04045) return v / 12.92;
  return std::pow((v + 0.055) / 1.055, 2.4);
}

Histogram display_histogram(const RgbaImage& img, LumaWeights weights) {
  std::vector<double> values(img.pixel_count());
  for (size_t i = 0; i < values.size(); ++i) {
    const float* p = &img.pixels[i * 4];
    double y = luminance(p[0], p[1], p[2], weights);
    if (std::isnan(y) || y == -std::numeric_limits<double>::infinity()) y = 0;
    if (y == std::numeric_limits<double>::infinity()) y = 1;
    values[i] = y;
  }
  return build(values, HistogramDomain::Display, weights, 0.0, 1.0);
}

Histogram log2_histogram(const RgbaImage& img, LumaWeights weights, double lo_stops,
                         double hi_stops) {
  if (!(hi_stops > lo_stops))
    throw CompError(fmt::format("log2 histogram: empty range [{:g}, {:g}]", lo_stops, hi_stops));
  std::vector<double> values(img.pixel_count());
  for (size_t i = 0; i < values.size(); ++i) {
    const float* p = &img.pixels[i * 4];
    const double y = luminance(p[0], p[1], p[2], weights);
    if (std::isnan(y) || y <= 0)
      values[i] = lo_stops;
    else if (std::isinf(y))
      values[i] = hi_stops;
    else
      values[i] = std::log2(y);
  }
  return build(values, HistogramDomain::Log2, weights, lo_stops, hi_stops);
}

double wasserstein1(const Histogram& a, const Histogram& b) {
  require_comparable(a, b, "wasserstein1");
  const double width = (a.hi - a.lo) / double(a.bins.size());
  double ca = 0, cb = 0, sum = 0;
  const double na = double(a.count), nb = double(b.count);
  // The CDFs step at the bins; between consecutive bins they differ by |ca - cb|.
  for (size_t i = 0; i + 1 < a.bins.size(); ++i) {
    ca += double(a.bins[i]) / na;
    cb += double(b.bins[i]) / nb;
    sum += std::abs(ca - cb);
  }
  return width * sum;
}

double matching_exposure_shift(const Histogram& image, const Histogram& reference) {
  if (image.domain != reference.domain)
    throw CompError(fmt::format("matching exposure: histograms of different domains ({} vs {})",
                                histogram_domain_name(image.domain),
                                histogram_domain_name(reference.domain)));
  if (image.count == 0 || reference.count == 0)
    throw CompError("matching exposure: empty histogram");
  if (image.domain == HistogramDomain::Log2) {
    if (image.median <= image.lo || reference.median <= reference.lo)
      throw CompError(
          "matching exposure: a median is at or below the bottom of the log2 range (black)");
    return reference.median - image.median;
  }
  const double img_lin = srgb_decode(image.median), ref_lin = srgb_decode(reference.median);
  if (!(img_lin > 0) || !(ref_lin > 0))
    throw CompError("matching exposure: a median luminance is black; no exposure shift matches it");
  return std::log2(ref_lin / img_lin);
}

nlohmann::json histogram_to_json(const Histogram& h, const Histogram* reference) {
  using nlohmann::json;
  auto one = [](const Histogram& x) {
    const auto w = luma_coefficients(x.weights);
    json p = json::object();
    for (const auto& [q, v] : x.percentiles) p[fmt::format("{:g}", q)] = v;
    return json{{"format", "vesper-histogram/1"},
                {"domain", histogram_domain_name(x.domain)},
                {"weights",
                 {{"name", luma_weights_name(x.weights)}, {"r", w[0]}, {"g", w[1]}, {"b", w[2]}}},
                {"range", {x.lo, x.hi}},
                {"bins", x.bins},
                {"count", x.count},
                {"mean", x.mean},
                {"median", x.median},
                {"percentiles", p},
                {"clipped", {{"low", x.clipped_low}, {"high", x.clipped_high}}}};
  };
  json j = one(h);
  if (reference) {
    j["reference"] = one(*reference);
    j["distance"] = {{"wasserstein1", wasserstein1(h, *reference)}};
    try {
      j["matching_exposure_stops"] = matching_exposure_shift(h, *reference);
    } catch (const CompError&) {
      j["matching_exposure_stops"] = nullptr;
    }
  }
  return j;
}

std::string histogram_json(const Histogram& h, const Histogram* reference) {
  return histogram_to_json(h, reference).dump(2) + "\n";
}

std::string terminal_histogram(const Histogram& h, int width, int height) {
  static const char* const kBlocks[] = {" ", "▁", "▂", "▃", "▄", "▅", "▆", "▇", "█"};
  const int nb = int(h.bins.size());
  width = std::clamp(width, 1, std::max(1, nb));
  height = std::max(1, height);
  std::vector<double> cols(size_t(width), 0.0);
  for (int c = 0; c < width; ++c) {
    const int b0 = c * nb / width, b1 = (c + 1) * nb / width;
    for (int b = b0; b < b1; ++b) cols[size_t(c)] += double(h.bins[size_t(b)]);
  }
  // Scale to the interior: a black background or blown highlights in the end
  // columns would flatten everything else; they are capped at full height.
  double top = 0;
  for (int c = 1; c + 1 < width; ++c) top = std::max(top, cols[size_t(c)]);
  if (top == 0)
    for (double v : cols) top = std::max(top, v);
  std::string out;
  for (int r = height - 1; r >= 0; --r) {
    std::string row;
    for (int c = 0; c < width; ++c) {
      const double v = cols[size_t(c)];
      // Eighths of a row; anything non-zero shows at least a sliver.
      long level = top > 0 ? std::lround(std::min(1.0, v / top) * height * 8) : 0;
      if (v > 0 && level == 0) level = 1;
      const long here = std::clamp(level - long(r) * 8, 0L, 8L);
      row += kBlocks[here];
    }
    while (!row.empty() && row.back() == ' ') row.pop_back();
    out += row + "\n";
  }
  const char* unit = h.domain == HistogramDomain::Log2 ? " stops" : "";
  out += fmt::format(
      "[{:g}, {:g}]{}  median {:.4g}  mean {:.4g}  clipped {} low, {} high  ({} px, {})\n", h.lo,
      h.hi, unit, h.median, h.mean, pct(h.clipped_low), pct(h.clipped_high), h.count,
      luma_weights_name(h.weights));
  return out;
}

HistogramSource read_histogram_source(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw CompError(path.string() + ": no such file");
  if (std::filesystem::is_directory(path, ec))
    throw CompError(path.string() + ": is a directory, not an image");
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "not an image OpenImageIO can read";
    throw CompError(path.string() + ": cannot read the image: " + why);
  }
  const OIIO::ImageSpec spec = in->spec();
  const int nc = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || nc <= 0)
    throw CompError(path.string() + ": empty image (" + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + ")");
  std::vector<float> px(size_t(spec.width) * size_t(spec.height) * size_t(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, px.data())) {
    std::string why = in->geterror();
    throw CompError(path.string() + ": cannot read the image (corrupt or truncated?): " + why);
  }
  in->close();
  auto find = [&](const char* name) {
    for (int c = 0; c < nc; ++c)
      if (spec.channelnames.size() > size_t(c) && spec.channelnames[size_t(c)] == name) return c;
    return -1;
  };
  int r = find("R"), g = find("G"), b = find("B");
  if (r < 0 || g < 0 || b < 0) {
    if (nc >= 3) {
      r = 0, g = 1, b = 2;
    } else if (nc == 1 || nc == 2) {  // grey (+ alpha)
      r = g = b = 0;
    } else {
      throw CompError(path.string() + ": no R, G, B channels");
    }
  }
  HistogramSource s;
  s.format = in->format_name();
  s.scene_linear = s.format == "openexr" || s.format == "hdr";
  s.image = RgbaImage(spec.width, spec.height);
  const int a = spec.alpha_channel;
  for (size_t i = 0; i < s.image.pixel_count(); ++i) {
    const float* p = &px[i * size_t(nc)];
    float* q = &s.image.pixels[i * 4];
    q[0] = p[r];
    q[1] = p[g];
    q[2] = p[b];
    q[3] = a >= 0 && a < nc ? p[a] : 1.f;
  }
  return s;
}

}  // namespace vesper
