// The histogram as a picture: 800x400 RGB, dark background, the histogram as
// a light grey filled area (fraction of pixels per bin), the reference as a
// blue step outline, gridlines at quarters, the medians as vertical lines,
// clipped fractions as red bars at the sides, and a key strip underneath that
// shows which grey each position of the axis is.
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "compositor/histogram.h"
#include "compositor/histogram_scale.h"

namespace vesper {

namespace {

using Rgb8 = std::array<uint8_t, 3>;

constexpr int kW = 800, kH = 400;
constexpr int kX0 = 16, kX1 = 784;  // plot area columns [kX0, kX1): 3 px per bin
constexpr int kY0 = 16, kY1 = 352;  // plot area rows [kY0, kY1), bars grow up from kY1
constexpr int kKeyY0 = 358, kKeyY1 = 370;

constexpr Rgb8 kBackground{18, 18, 22}, kPlotArea{28, 28, 34}, kGrid{58, 58, 68},
    kFill{185, 185, 192}, kEdge{240, 240, 240}, kCapped{235, 130, 90}, kReference{80, 170, 255},
    kMedian{255, 200, 60}, kClipped{230, 70, 60}, kTick{150, 150, 160};

struct Canvas {
  std::vector<uint8_t> px = std::vector<uint8_t>(size_t(kW) * kH * 3);
  void set(int x, int y, Rgb8 c, double alpha = 1.0) {
    if (x < 0 || y < 0 || x >= kW || y >= kH) return;
    uint8_t* p = &px[(size_t(y) * kW + size_t(x)) * 3];
    alpha = std::clamp(alpha, 0.0, 1.0);
    for (int i = 0; i < 3; ++i)
      p[i] = uint8_t(std::lround(p[i] * (1 - alpha) + c[size_t(i)] * alpha));
  }
  void rect(int x0, int y0, int x1, int y1, Rgb8 c, double alpha = 1.0) {  // [x0,x1) x [y0,y1)
    for (int y = std::max(0, y0); y < std::min(kH, y1); ++y)
      for (int x = std::max(0, x0); x < std::min(kW, x1); ++x) set(x, y, c, alpha);
  }
};

// Height (pixels, fractional) of a fraction under the common scale.
double bar_height(double f, double top) {
  return top > 0 ? std::min(1.0, f / top) * double(kY1 - kY0) : 0.0;
}

int value_to_x(const Histogram& h, double v) {
  const double t = std::clamp((v - h.lo) / (h.hi - h.lo), 0.0, 1.0);
  return kX0 + int(std::lround(t * double(kX1 - kX0 - 1)));
}

// The display grey of a position t in [0, 1] along the axis.
uint8_t key_grey(const Histogram& h, double t) {
  double v = t;
  if (h.domain == HistogramDomain::Log2)
    v = srgb_encode(std::min(1.0, std::exp2(h.lo + t * (h.hi - h.lo))));
  return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

// A small downward triangle in the top margin, pointing at column x.
void marker(Canvas& c, int x, Rgb8 colour) {
  for (int row = 0; row < 7; ++row)
    c.rect(x + 1 - (6 - row), 4 + row, x + 1 + (6 - row) + 1, 5 + row, colour);
}

// Gridlines at quarters of the range and of the scale.
void draw_grid(Canvas& c) {
  for (int q = 1; q < 4; ++q) {
    const int x = kX0 + (kX1 - kX0) * q / 4;
    c.rect(x, kY0, x + 1, kY1, kGrid);
    const int y = kY1 - (kY1 - kY0) * q / 4;
    c.rect(kX0, y, kX1, y + 1, kGrid);
  }
}

// The histogram: a filled area, anti-aliased at the top, with a bright edge.
void draw_fill(Canvas& c, const std::vector<double>& f, double top) {
  const int nb = int(f.size()), plot_w = kX1 - kX0;
  for (int x = kX0; x < kX1; ++x) {
    const int bin = std::min(nb - 1, (x - kX0) * nb / plot_w);
    const double v = f[size_t(bin)];
    if (v <= 0) continue;
    const double hp = std::max(1.0, bar_height(v, top));
    const int full = int(std::floor(hp));
    c.rect(x, kY1 - full, x + 1, kY1, kFill);
    c.set(x, kY1 - full - 1, kFill, hp - full);
    const bool capped = top > 0 && v > top;
    c.set(x, kY1 - full, capped ? kCapped : kEdge);
    if (capped) c.rect(x, kY0, x + 1, kY0 + 6, kCapped);
  }
}

// The reference: a 2 px step outline, and its median dashed.
void draw_reference(Canvas& c, const Histogram& h, const Histogram& reference,
                    const std::vector<double>& fr, double top) {
  const int nb = int(fr.size()), plot_w = kX1 - kX0;
  int prev_y = kY1;
  for (int i = 0; i < nb; ++i) {
    const int xa = kX0 + i * plot_w / nb, xb = kX0 + (i + 1) * plot_w / nb;
    const int y = kY1 - int(std::lround(bar_height(fr[size_t(i)], top)));
    if (y != prev_y)
      c.rect(xa, std::min(prev_y, y) - 1, xa + 2, std::max(prev_y, y) + 1, kReference, 0.9);
    if (fr[size_t(i)] > 0) c.rect(xa, y - 1, xb, y + 1, kReference, 0.9);
    prev_y = y;
  }
  if (prev_y != kY1) c.rect(kX1 - 2, prev_y - 1, kX1, kY1, kReference, 0.9);
  const int xm = value_to_x(h, reference.median);
  for (int y = kY0; y < kY1; y += 8) c.rect(xm, y, xm + 2, std::min(kY1, y + 4), kReference);
  marker(c, xm, kReference);
}

// Clipped fractions: red bars in the side margins, height = fraction of the plot.
void draw_clipped(Canvas& c, const Histogram& h) {
  auto clip_bar = [&](double frac, int x0) {
    if (frac <= 0) return;
    const int hp = std::max(2, int(std::lround(frac * double(kY1 - kY0))));
    c.rect(x0, kY1 - hp, x0 + 8, kY1, kClipped);
  };
  clip_bar(h.clipped_low, 4);
  clip_bar(h.clipped_high, kW - 12);
}

// Key strip: the grey of each position of the axis, and ticks.
void draw_key(Canvas& c, const Histogram& h) {
  const int plot_w = kX1 - kX0;
  for (int x = kX0; x < kX1; ++x) {
    const uint8_t g = key_grey(h, double(x - kX0) / double(plot_w - 1));
    c.rect(x, kKeyY0, x + 1, kKeyY1, Rgb8{g, g, g});
  }
  for (int q = 0; q <= 4; ++q) {
    const int x = std::min(kX1 - 1, kX0 + plot_w * q / 4);
    c.rect(x, kKeyY1 + 2, x + 1, kKeyY1 + 10, kTick);
  }
  if (h.domain == HistogramDomain::Log2) {  // a short tick per stop, a long one at 0 stops
    for (double s = std::ceil(h.lo); s <= h.hi; s += 1) {
      const int x = value_to_x(h, s);
      c.rect(x, kKeyY1 + 2, x + 1, kKeyY1 + (s == 0 ? 14 : 5), s == 0 ? kMedian : kTick);
    }
  }
}

// Written next to the target and renamed, so a failure leaves nothing behind.
void write_png(const Canvas& c, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out)
    throw CompError(path.string() + ": cannot write a plot in this format: " + OIIO::geterror());
  const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
  OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(tmp.string(), spec))
    throw CompError(path.string() + ": cannot write the plot: " + out->geterror());
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, c.px.data());
  const bool closed = out->close();
  std::error_code ec;
  if (!ok || !closed) {
    const std::string err = out->geterror();
    fs::remove(tmp, ec);
    throw CompError(path.string() + ": cannot write the plot: " + err);
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw CompError(path.string() + ": cannot move the finished plot into place: " + ec.message());
  }
}

}  // namespace

std::vector<double> histogram_fractions(const Histogram& h) {
  std::vector<double> f(h.bins.size(), 0.0);
  if (h.count == 0) return f;
  for (size_t i = 0; i < f.size(); ++i) f[i] = double(h.bins[i]) / double(h.count);
  return f;
}

// Common scale from the interior bins (a black background or blown
// highlights in an end bin would flatten the rest); 5% headroom.
double histogram_plot_scale(const std::vector<double>& f, const std::vector<double>& fr) {
  const size_t nb = f.size();
  double top = 0;
  for (size_t i = 1; i + 1 < nb; ++i) {
    top = std::max(top, f[i]);
    if (i < fr.size()) top = std::max(top, fr[i]);
  }
  if (top == 0) {
    for (double v : f) top = std::max(top, v);
    for (double v : fr) top = std::max(top, v);
  }
  return top * 1.05;
}

void write_histogram_png(const Histogram& h, const std::filesystem::path& path,
                         const Histogram* reference) {
  if (h.bins.empty()) throw CompError(path.string() + ": cannot plot a histogram without bins");
  if (reference && reference->bins.size() != h.bins.size())
    throw CompError(path.string() + ": the reference histogram has a different number of bins");
  Canvas c;
  c.rect(0, 0, kW, kH, kBackground);
  c.rect(kX0, kY0, kX1, kY1, kPlotArea);
  const std::vector<double> f = histogram_fractions(h);
  const std::vector<double> fr =
      reference ? histogram_fractions(*reference) : std::vector<double>{};
  const double top = histogram_plot_scale(f, fr);
  draw_grid(c);
  // Median of the image: a line behind the histogram and a marker above the plot.
  if (h.count > 0) {
    const int xm = value_to_x(h, h.median);
    c.rect(xm, kY0, xm + 2, kY1, kMedian, 0.85);
    marker(c, xm, kMedian);
  }
  draw_fill(c, f, top);
  if (reference) draw_reference(c, h, *reference, fr, top);
  draw_clipped(c, h);
  draw_key(c, h);
  write_png(c, path);
}

}  // namespace vesper
