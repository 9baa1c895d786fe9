#pragma once
// What the report's SVG charts share: a plot area that maps data to pixels,
// "nice" tick values, the accessible <svg> opening, axes with gridlines and
// labels, and a legend. Charts are text, inline in the page: no script, no
// network, readable by screen readers through their <title> and <desc>.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vesper::regress {

struct PlotFrame {
  double width = 520, height = 250;                     // the whole SVG, px
  double left = 60, right = 14, top = 30, bottom = 62;  // margins around the plot area
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;        // data range of the plot area

  double px(double x) const;  // data -> SVG x
  double py(double y) const;  // data -> SVG y (up is bigger)
  double plot_left() const { return left; }
  double plot_right() const { return width - right; }
  double plot_top() const { return top; }
  double plot_bottom() const { return height - bottom; }
};

// About `target` round values (1, 2 or 5 times a power of ten) from the
// first at or below `lo` to the first at or above `hi`; [lo, hi] widened
// when empty.
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

// A tick value with the decimals its step needs, trailing zeros dropped
// ("-2", "-1.75", "0.5"), so float steps never show as 0.6000000000000001.
std::string tick_label(double value, double step);

// <svg ... role="img" aria-labelledby> with <title> and <desc>; close with
// "</svg>". No xmlns: inline SVG in HTML needs none, and the page holds no
// http(s) URL at all.
std::string svg_open(const PlotFrame& frame, std::string_view id, std::string_view title,
                     std::string_view description);

struct AxisTick {
  double value;
  std::string label;
};

// The plot area's background, horizontal gridlines with labels at y ticks,
// x tick labels, and the axis titles (y rotated along the left edge).
std::string svg_axes(const PlotFrame& frame, const std::vector<AxisTick>& y_ticks,
                     const std::vector<AxisTick>& x_ticks, std::string_view x_title,
                     std::string_view y_title);

// A legend row along the bottom edge: each entry an SVG swatch drawn in a
// 24x12 box at the origin (translated into place) and its label.
struct LegendEntry {
  std::string swatch;
  std::string label;
};
std::string svg_legend(const PlotFrame& frame, const std::vector<LegendEntry>& entries);

// "M x y L x y ..." through the points (SVG coordinates).
std::string svg_path(const std::vector<std::pair<double, double>>& points);

// A number as SVG attributes want it: at most 2 decimals, no trailing zeros.
std::string svg_number(double v);

}  // namespace vesper::regress
