#include "regress/histogram_chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "compositor/histogram_scale.h"
#include "regress/html_text.h"
#include "regress/svg_plot.h"

namespace vesper::regress {

namespace {

double bin_edge(const Histogram& h, size_t i) {
  return h.lo + (h.hi - h.lo) * double(i) / double(h.bins.size());
}

// The bins [first, last] where either histogram has pixels.
std::pair<size_t, size_t> occupied_bins(const Histogram& a, const Histogram& b) {
  size_t first = a.bins.size(), last = 0;
  for (size_t i = 0; i < a.bins.size(); ++i)
    if (a.bins[i] > 0 || (i < b.bins.size() && b.bins[i] > 0)) {
      first = std::min(first, i);
      last = i;
    }
  if (first > last) return {0, a.bins.size() - 1};
  return {first, last};
}

// The outline of bins [first, last] as steps (percent of pixels, capped at the top).
std::vector<std::pair<double, double>> steps(const PlotFrame& f, const Histogram& h,
                                             const std::vector<double>& fractions, size_t first,
                                             size_t last) {
  std::vector<std::pair<double, double>> points;
  points.emplace_back(f.px(bin_edge(h, first)), f.py(0));
  for (size_t i = first; i <= last; ++i) {
    const double y = f.py(std::min(fractions[i] * 100.0, f.y_hi));
    points.emplace_back(f.px(bin_edge(h, i)), y);
    points.emplace_back(f.px(bin_edge(h, i + 1)), y);
  }
  points.emplace_back(f.px(bin_edge(h, last + 1)), f.py(0));
  return points;
}

std::string median_line(const PlotFrame& f, double median, const char* css_class) {
  const std::string x = svg_number(f.px(std::clamp(median, f.x_lo, f.x_hi)));
  return fmt::format("<line class=\"{}\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>", css_class, x,
                     svg_number(f.plot_top()), x, svg_number(f.plot_bottom()));
}

}  // namespace

std::string histogram_overlay_svg(const Histogram& golden, const Histogram& fresh,
                                  std::string_view id, std::string_view title, double distance) {
  const std::vector<double> fg = histogram_fractions(golden), fn = histogram_fractions(fresh);
  const double top = histogram_plot_scale(fn, fg) * 100.0;
  const auto [first, last] = occupied_bins(golden, fresh);
  PlotFrame f;
  f.x_lo = std::max(golden.lo, std::floor(bin_edge(golden, first) - 0.5));  // half a stop clear
  f.x_hi = std::min(golden.hi, std::ceil(bin_edge(golden, last + 1) + 0.5));
  const std::vector<double> yt = nice_ticks(0, top > 0 ? top : 1.0, 4);
  f.y_hi = yt.back();
  std::vector<AxisTick> y_ticks, x_ticks;
  for (double t : yt) y_ticks.push_back({t, tick_label(t, yt[1] - yt[0]) + " %"});
  const std::vector<double> xt = nice_ticks(f.x_lo, f.x_hi, 8);
  for (double t : xt)
    if (t >= f.x_lo - 1e-9 && t <= f.x_hi + 1e-9)
      x_ticks.push_back({t, tick_label(t, xt[1] - xt[0])});
  const std::string description = fmt::format(
      "Luminosity histograms: golden median {} stops, new median {} stops; Wasserstein-1 "
      "distance {} stops",
      format_figure(golden.median, 3), format_figure(fresh.median, 3), format_figure(distance, 3));
  std::string s = svg_open(f, id, title, description);
  s += fmt::format("<text class=\"chart-title\" x=\"{}\" y=\"18\">{}</text>",
                   svg_number(f.plot_left()), html_escape(title));
  s += svg_axes(f, y_ticks, x_ticks, "log2 luminance (stops)", "pixels");
  s += fmt::format("<path class=\"h-golden\" d=\"{} Z\"/>",
                   svg_path(steps(f, golden, fg, first, last)));
  s += fmt::format("<path class=\"h-new\" d=\"{}\"/>", svg_path(steps(f, fresh, fn, first, last)));
  s += median_line(f, golden.median, "median-golden");
  s += median_line(f, fresh.median, "median-new");
  s += svg_legend(
      f, {{"<rect class=\"h-golden\" x=\"0\" y=\"0\" width=\"24\" height=\"12\"/>", "golden"},
          {"<line class=\"h-new\" x1=\"0\" y1=\"6\" x2=\"24\" y2=\"6\"/>", "new"},
          {"<line class=\"median-golden\" x1=\"0\" y1=\"6\" x2=\"24\" y2=\"6\"/>", "golden median"},
          {"<line class=\"median-new\" x1=\"0\" y1=\"6\" x2=\"24\" y2=\"6\"/>", "new median"}});
  return s + "</svg>";
}

}  // namespace vesper::regress
