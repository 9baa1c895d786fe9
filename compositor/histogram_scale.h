#pragma once
// The plot maths every histogram picture shares (the PNG plot, the regression
// report's SVG): bins as fractions of the pixel count, and one vertical scale
// for an image and its reference that an end bin (a black background, blown
// highlights) cannot flatten.
#include <vector>

#include "compositor/histogram.h"

namespace vesper {

// bins[i] / count (all zero for an empty histogram).
std::vector<double> histogram_fractions(const Histogram& h);

// The fraction at the top of the plot: the largest interior bin of either
// (the end bins only if every interior bin is empty), with 5 % headroom. Bins
// above it are drawn capped. `reference` may be empty.
double histogram_plot_scale(const std::vector<double>& fractions,
                            const std::vector<double>& reference);

}  // namespace vesper
