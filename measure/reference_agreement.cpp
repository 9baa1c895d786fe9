#include "measure/reference_agreement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "measure/beauty.h"

namespace vesper::measure {
namespace {

// Mean of R, G, B over the pixels of [x0, x1) x [y0, y1).
double region_mean(const LayeredImage& img, int x0, int y0, int x1, int y1) {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (size_t c = 0; c < 3; ++c) sum += img.at(x, y, c);
  const double n = 3.0 * double(x1 - x0) * double(y1 - y0);
  return n > 0 ? sum / n : 0;
}

// Nearest-rank percentile of sorted values, q in [0, 1].
double percentile(const std::vector<double>& sorted, double q) {
  const size_t rank = size_t(std::ceil(q * double(sorted.size())));
  return sorted[std::clamp<size_t>(rank, 1, sorted.size()) - 1];
}

std::vector<double> block_ratios(const LayeredImage& a, const LayeredImage& b,
                                 const AgreementBands& bands) {
  std::vector<double> ratios;
  const int s = std::max(1, bands.block_size);
  for (int y = 0; y < a.height; y += s)
    for (int x = 0; x < a.width; x += s) {
      const int x1 = std::min(a.width, x + s), y1 = std::min(a.height, y + s);
      const double ma = region_mean(a, x, y, x1, y1), mb = region_mean(b, x, y, x1, y1);
      if (ma < bands.min_block_mean || mb < bands.min_block_mean) continue;
      ratios.push_back(ma / mb);
    }
  std::sort(ratios.begin(), ratios.end());
  return ratios;
}

void flag_outside(ReferenceAgreement& r, const std::string& what, double v, double lo, double hi) {
  if (v >= lo && v <= hi) return;
  r.flagged = true;
  r.reasons.push_back(fmt::format("{} {:.3g} outside [{:.3g}, {:.3g}]", what, v, lo, hi));
}

}  // namespace

ReferenceAgreement compare_references(const LayeredImage& a_in, const LayeredImage& b_in,
                                      const AgreementBands& bands) {
  const LayeredImage a = beauty_rgb(a_in), b = beauty_rgb(b_in);
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("compare_references: the references differ in size");
  ReferenceAgreement r;
  const double ma = region_mean(a, 0, 0, a.width, a.height);
  const double mb = region_mean(b, 0, 0, b.width, b.height);
  r.mean_ratio = mb > 0 ? ma / mb : (ma > 0 ? INFINITY : 1.0);
  flag_outside(r, "image mean ratio", r.mean_ratio, bands.mean_ratio_lo, bands.mean_ratio_hi);
  const std::vector<double> ratios = block_ratios(a, b, bands);
  r.blocks = int(ratios.size());
  if (ratios.empty()) return r;
  r.block_min = ratios.front();
  r.block_max = ratios.back();
  r.block_p05 = percentile(ratios, 0.05);
  r.block_p95 = percentile(ratios, 0.95);
  flag_outside(r, "5th percentile of block ratios", r.block_p05, bands.block_ratio_lo,
               bands.block_ratio_hi);
  flag_outside(r, "95th percentile of block ratios", r.block_p95, bands.block_ratio_lo,
               bands.block_ratio_hi);
  return r;
}

}  // namespace vesper::measure
