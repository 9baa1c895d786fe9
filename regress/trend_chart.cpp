#include "regress/trend_chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "regress/html_text.h"
#include "regress/svg_plot.h"

namespace vesper::regress {

namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

struct FigureText {
  const char* title;
  const char* y_title;
  const char* legend;
};

FigureText figure_text(TrendFigure figure) {
  switch (figure) {
    case TrendFigure::RenderSeconds:
      return {"Render time", "seconds", "render time"};
    case TrendFigure::MaxAbsZ:
      return {"Largest |Z| (difference from the golden)", "|Z|", "largest |Z|"};
    case TrendFigure::MinDetectableChange:
      return {"Smallest detectable change (noise)", "% of the tile mean", "detectable change"};
  }
  return {"", "", ""};
}

// The figure of a run, or NaN when the run has none (reused: not rendered;
// error: nothing compared).
double figure_value(const TrendPoint& p, TrendFigure figure) {
  switch (figure) {
    case TrendFigure::RenderSeconds:
      return p.reused || p.render_seconds <= 0 ? kNoValue : p.render_seconds;
    case TrendFigure::MaxAbsZ:
      return p.verdict == Verdict::Error ? kNoValue : p.max_abs_z;
    case TrendFigure::MinDetectableChange:
      return p.min_detectable_change > 0 ? p.min_detectable_change * 100.0 : kNoValue;
  }
  return kNoValue;
}

std::string value_text(double v, TrendFigure figure) {
  if (std::isnan(v)) return "no value";
  if (figure == TrendFigure::RenderSeconds) return format_seconds(v);
  if (figure == TrendFigure::MinDetectableChange) return format_figure(v, 2) + " %";
  return format_figure(v, 3);
}

// "2024-05-01T02:00:00Z" -> "05-01 02:00"; anything else as it is.
std::string short_date(const std::string& iso) {
  if (iso.size() >= 16 && iso[4] == '-' && iso[10] == 'T')
    return iso.substr(5, 5) + " " + iso.substr(11, 5);
  return iso;
}

// The verdict as a marker shape centred at the origin.
std::string marker(Verdict v) {
  switch (v) {
    case Verdict::Pass:
      return "<circle class=\"m-pass\" r=\"4\"/>";
    case Verdict::Regressed:
      return "<path class=\"m-regressed\" d=\"M0 -5.5 L5 4 L-5 4 Z\"/>";
    case Verdict::Error:
      return "<rect class=\"m-error\" x=\"-4\" y=\"-4\" width=\"8\" height=\"8\"/>";
  }
  return "";
}

std::vector<AxisTick> x_ticks(const std::vector<TrendPoint>& points) {
  std::vector<AxisTick> ticks;
  const size_t n = points.size(), step = std::max<size_t>(1, (n + 4) / 5);
  for (size_t i = 0; i < n; i += step)
    ticks.push_back({double(i), short_date(points[i].started_at)});
  if (n > 1 && (n - 1) % step != 0)
    ticks.push_back({double(n - 1), short_date(points.back().started_at)});
  return ticks;
}

// The line through the runs that have a value (a gap where one has none),
// and every run's marker (at the bottom when it has no value).
std::string series(const PlotFrame& f, const std::vector<TrendPoint>& points,
                   const std::vector<double>& values, TrendFigure figure) {
  std::string s;
  std::vector<std::pair<double, double>> run;
  auto flush = [&] {
    if (run.size() > 1) s += fmt::format("<path class=\"line\" d=\"{}\"/>", svg_path(run));
    run.clear();
  };
  for (size_t i = 0; i < points.size(); ++i) {
    if (std::isnan(values[i])) {
      flush();
      continue;
    }
    run.emplace_back(f.px(double(i)), f.py(values[i]));
  }
  flush();
  for (size_t i = 0; i < points.size(); ++i) {
    const double y = std::isnan(values[i]) ? f.plot_bottom() : f.py(values[i]);
    const std::string note = points[i].reused ? ", reused: not re-rendered" : "";
    s += fmt::format("<g transform=\"translate({} {})\"><title>{}: {}, {}{}</title>{}</g>",
                     svg_number(f.px(double(i))), svg_number(y), html_escape(points[i].started_at),
                     value_text(values[i], figure), verdict_name(points[i].verdict), note,
                     marker(points[i].verdict));
  }
  return s;
}

}  // namespace

std::vector<TrendPoint> scene_trend(const std::vector<TrendPoint>* history, const RunResult& run,
                                    std::string_view scene, size_t limit) {
  std::vector<TrendPoint> points;
  if (history)
    for (const TrendPoint& p : *history)
      if (p.scene == scene) points.push_back(p);
  const bool has_run = std::any_of(points.begin(), points.end(), [&](const TrendPoint& p) {
    return p.started_at == run.started_at;
  });
  if (!has_run)
    for (const TrendPoint& p : trend_points(run))
      if (p.scene == scene) points.push_back(p);
  std::stable_sort(points.begin(), points.end(), [](const TrendPoint& a, const TrendPoint& b) {
    return a.started_at < b.started_at;
  });
  if (points.size() > limit) points.erase(points.begin(), points.end() - std::ptrdiff_t(limit));
  return points;
}

std::string trend_chart_svg(const std::vector<TrendPoint>& points, TrendFigure figure,
                            std::string_view id, std::optional<double> reference) {
  const FigureText text = figure_text(figure);
  std::vector<double> values;
  double top = reference.value_or(0);
  for (const TrendPoint& p : points) {
    values.push_back(figure_value(p, figure));
    if (!std::isnan(values.back())) top = std::max(top, values.back());
  }
  PlotFrame f;
  f.x_lo = -0.5;
  f.x_hi = std::max(0.5, double(points.size()) - 0.5);
  const std::vector<double> ticks = nice_ticks(0, top > 0 ? top * 1.05 : 1.0, 4);
  f.y_hi = ticks.back();
  std::vector<AxisTick> y_ticks;
  for (double t : ticks) y_ticks.push_back({t, tick_label(t, ticks[1] - ticks[0])});
  const std::string description =
      fmt::format("{} over {} runs; latest {}: {}", text.title, points.size(),
                  points.empty() ? std::string("none") : points.back().started_at,
                  points.empty() ? std::string("no value") : value_text(values.back(), figure));
  std::string s = svg_open(f, id, text.title, description);
  s += fmt::format("<text class=\"chart-title\" x=\"{}\" y=\"18\">{}</text>",
                   svg_number(f.plot_left()), html_escape(text.title));
  s += svg_axes(f, y_ticks, x_ticks(points), "run (UTC)", text.y_title);
  std::vector<LegendEntry> legend{
      {"<line class=\"line\" x1=\"0\" y1=\"6\" x2=\"24\" y2=\"6\"/>", text.legend}};
  if (reference) {
    s += fmt::format("<line class=\"reference\" x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\"/>",
                     svg_number(f.plot_left()), svg_number(f.plot_right()),
                     svg_number(f.py(*reference)));
    legend.push_back(
        {"<line class=\"reference\" x1=\"0\" y1=\"6\" x2=\"24\" y2=\"6\"/>", "golden"});
  }
  s += series(f, points, values, figure);
  for (Verdict v : {Verdict::Pass, Verdict::Regressed, Verdict::Error})
    legend.push_back({"<g transform=\"translate(12 6)\">" + marker(v) + "</g>", verdict_name(v)});
  s += svg_legend(f, legend);
  return s + "</svg>";
}

}  // namespace vesper::regress
