#pragma once
// The golden's and the new render's luminosity histograms overlaid, as an
// inline SVG: the golden a filled grey area, the new one a dark step line,
// their medians as vertical lines (golden dashed). The x range is cut to the
// stops where either has pixels.
#include <string>
#include <string_view>

#include "compositor/histogram.h"

namespace vesper::regress {

// Both histograms of the same domain, range and bin count (log2 stops, as
// the comparison's histogram distance uses); `distance` their Wasserstein-1
// distance, shown in the description. `id` unique in the page.
std::string histogram_overlay_svg(const Histogram& golden, const Histogram& fresh,
                                  std::string_view id, std::string_view title, double distance);

}  // namespace vesper::regress
