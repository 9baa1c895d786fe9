#include "regress/svg_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "regress/html_text.h"

namespace vesper::regress {

double PlotFrame::px(double x) const {
  const double span = x_hi > x_lo ? x_hi - x_lo : 1.0;
  return plot_left() + (x - x_lo) / span * (plot_right() - plot_left());
}

double PlotFrame::py(double y) const {
  const double span = y_hi > y_lo ? y_hi - y_lo : 1.0;
  return plot_bottom() - (y - y_lo) / span * (plot_bottom() - plot_top());
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
  if (hi <= lo) hi = lo + (lo == 0 ? 1.0 : std::fabs(lo) * 0.5);
  const double raw = (hi - lo) / std::max(1, target);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  std::vector<double> ticks;
  const double first = std::floor(lo / step + 1e-9);
  for (double i = first; (i - 1) * step < hi - step * 1e-9; i += 1) ticks.push_back(i * step);
  return ticks;
}

std::string tick_label(double value, double step) {
  int decimals = 0;
  while (decimals < 6) {
    const double scaled = step * std::pow(10.0, decimals);
    if (std::fabs(scaled - std::round(scaled)) < 1e-6 * std::max(1.0, scaled)) break;
    ++decimals;
  }
  return trimmed_fixed(value, decimals);
}

std::string svg_number(double v) { return trimmed_fixed(v, 2); }

std::string svg_open(const PlotFrame& frame, std::string_view id, std::string_view title,
                     std::string_view description) {
  const std::string w = svg_number(frame.width), h = svg_number(frame.height);
  const std::string sid = html_escape(id);
  return fmt::format(
      "<svg class=\"chart\" viewBox=\"0 0 {0} {1}\" "
      "width=\"{0}\" height=\"{1}\" role=\"img\" aria-labelledby=\"{2}-t {2}-d\">"
      "<title id=\"{2}-t\">{3}</title><desc id=\"{2}-d\">{4}</desc>",
      w, h, sid, html_escape(title), html_escape(description));
}

std::string svg_axes(const PlotFrame& f, const std::vector<AxisTick>& y_ticks,
                     const std::vector<AxisTick>& x_ticks, std::string_view x_title,
                     std::string_view y_title) {
  const std::string l = svg_number(f.plot_left()), r = svg_number(f.plot_right());
  const std::string t = svg_number(f.plot_top()), b = svg_number(f.plot_bottom());
  std::string s = fmt::format(
      "<rect class=\"plot-area\" x=\"{0}\" y=\"{1}\" width=\"{2}\" height=\"{3}\"/>", l, t,
      svg_number(f.plot_right() - f.plot_left()), svg_number(f.plot_bottom() - f.plot_top()));
  for (const AxisTick& tick : y_ticks) {
    const std::string y = svg_number(f.py(tick.value));
    s += fmt::format("<line class=\"grid\" x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\"/>", l, r, y);
    s += fmt::format("<text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>",
                     svg_number(f.plot_left() - 6), svg_number(f.py(tick.value) + 4),
                     html_escape(tick.label));
  }
  for (const AxisTick& tick : x_ticks) {
    const std::string x = svg_number(f.px(tick.value));
    s += fmt::format("<line class=\"axis\" x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\"/>", x, b,
                     svg_number(f.plot_bottom() + 4));
    s += fmt::format("<text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>", x,
                     svg_number(f.plot_bottom() + 16), html_escape(tick.label));
  }
  s += fmt::format("<line class=\"axis\" x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\"/>", l, r, b);
  s += fmt::format("<text class=\"axis-title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
                   svg_number((f.plot_left() + f.plot_right()) / 2),
                   svg_number(f.plot_bottom() + 32), html_escape(x_title));
  const double ym = (f.plot_top() + f.plot_bottom()) / 2;
  s += fmt::format(
      "<text class=\"axis-title\" transform=\"translate(14 {}) rotate(-90)\" "
      "text-anchor=\"middle\">{}</text>",
      svg_number(ym), html_escape(y_title));
  return s;
}

std::string svg_legend(const PlotFrame& f, const std::vector<LegendEntry>& entries) {
  std::string s = "<g class=\"legend\">";
  double x = f.plot_left();
  const double y = f.height - 16;
  for (const LegendEntry& e : entries) {
    s += fmt::format("<g transform=\"translate({} {})\">{}</g>", svg_number(x), svg_number(y - 9),
                     e.swatch);
    s += fmt::format("<text class=\"tick\" x=\"{}\" y=\"{}\">{}</text>", svg_number(x + 28),
                     svg_number(y + 1), html_escape(e.label));
    x += 40 + 6.5 * double(e.label.size());  // about the width of the label at 11 px
  }
  return s + "</g>";
}

std::string svg_path(const std::vector<std::pair<double, double>>& points) {
  std::string d;
  for (size_t i = 0; i < points.size(); ++i)
    d += fmt::format("{}{} {} ", i == 0 ? 'M' : 'L', svg_number(points[i].first),
                     svg_number(points[i].second));
  if (!d.empty()) d.pop_back();
  return d;
}

}  // namespace vesper::regress
