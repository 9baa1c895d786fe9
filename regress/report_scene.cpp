// One scene's part of the HTML report (report_sections.h).
#include <fmt/format.h>

#include "regress/html_text.h"
#include "regress/report_sections.h"
#include "regress/trend_chart.h"

namespace vesper::regress {

namespace {

const char* verdict_symbol(Verdict v) {
  switch (v) {
    case Verdict::Pass:
      return "&#10003;";  // check mark
    case Verdict::Regressed:
      return "&#10007;";  // ballot x
    case Verdict::Error:
      return "&#9888;";  // warning sign
  }
  return "";
}

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string list_items(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += "<li>" + html_escape(l) + "</li>";
  return s;
}

// What the verdict rests on: an error's reasons in an alert box, a
// regression's as a list, a pass's strength.
std::string verdict_explanation(const SceneResult& scene) {
  if (scene.verdict == Verdict::Error)
    return "<div class=\"error-box\" role=\"alert\"><strong>Error: this scene was not "
           "compared.</strong><ul>" +
           list_items(scene.reasons) + "</ul></div>";
  std::string s;
  if (!scene.reasons.empty()) s += "<ul class=\"reasons\">" + list_items(scene.reasons) + "</ul>";
  if (scene.verdict == Verdict::Pass) {
    const TrendPoint p = trend_point(scene, "");
    s += p.min_detectable_change > 0
             ? "<p class=\"power\">Nothing changed beyond Monte Carlo noise: could have detected "
               "changes &ge; " +
                   html_escape(format_percent(p.min_detectable_change)) +
                   " of a tile's mean (the weakest layer).</p>"
             : "<p class=\"power\">Nothing changed; no layer had variance channels, so the "
               "comparison had no noise model.</p>";
  }
  return s;
}

std::string timing_facts(const SceneResult& scene) {
  std::string s = "<dl class=\"facts\"><dt>Render time, golden &rarr; new</dt><dd>";
  s += render_time_text(scene);
  if (scene.reused) {
    s += " (the farm reused an identical task)";
  } else if (scene.new_seconds_repeats.size() > 1) {
    std::string repeats;
    for (double r : scene.new_seconds_repeats)
      repeats += (repeats.empty() ? "" : ", ") + format_seconds(r);
    s += "; new is the median of " + std::to_string(scene.new_seconds_repeats.size()) +
         " timings: " + html_escape(repeats);
  }
  s += "</dd>";
  auto fact = [&](const char* term, const std::string& value) {
    if (!value.empty()) s += fmt::format("<dt>{}</dt><dd>{}</dd>", term, value);
  };
  auto names = [](const std::vector<std::string>& v) {
    std::string out;
    for (const std::string& n : v)
      out += (out.empty() ? "" : ", ") + ("<code>" + html_escape(n) + "</code>");
    return out;
  };
  fact("Channels added", names(scene.channels_added));
  fact("Channels missing", names(scene.channels_missing));
  fact("Golden image",
       scene.golden_image.empty() ? "" : "<code>" + html_escape(scene.golden_image) + "</code>");
  fact("New image",
       scene.new_image.empty() ? "" : "<code>" + html_escape(scene.new_image) + "</code>");
  return s + "</dl>";
}

std::string trend_charts(const SceneResult& scene, const std::string& id,
                         const std::vector<TrendPoint>& trend) {
  std::string s = fmt::format("<h3>Across runs ({} kept in the history)</h3><div class=\"charts\">",
                              trend.size());
  s += trend_chart_svg(
      trend, TrendFigure::RenderSeconds, id + "-time",
      scene.golden_seconds > 0 ? std::optional<double>(scene.golden_seconds) : std::nullopt);
  s += trend_chart_svg(trend, TrendFigure::MaxAbsZ, id + "-z");
  s += trend_chart_svg(trend, TrendFigure::MinDetectableChange, id + "-noise");
  return s + "</div>";
}

}  // namespace

std::string verdict_class(Verdict v) { return std::string("v-") + verdict_name(v); }

std::string verdict_badge(Verdict v, const char* css) {
  return fmt::format("<span class=\"{} {}\"><span aria-hidden=\"true\">{}</span> {}</span>", css,
                     verdict_class(v), verdict_symbol(v), upper(verdict_name(v)));
}

std::string render_time_text(const SceneResult& scene) {
  if (scene.reused) return "reused: not re-rendered";
  auto seconds = [](double s) { return s > 0 ? html_escape(format_seconds(s)) : "unknown"; };
  std::string s = seconds(scene.golden_seconds) + " &rarr; " + seconds(scene.new_seconds);
  if (scene.golden_seconds > 0 && scene.new_seconds > 0)
    s +=
        " (&times;" + html_escape(format_figure(scene.new_seconds / scene.golden_seconds, 3)) + ")";
  return s;
}

std::string scene_anchor(size_t index) { return "scene-" + std::to_string(index); }

std::string scene_section(const SceneResult& scene, size_t index, const ReportImages& images,
                          const std::vector<TrendPoint>& trend) {
  const std::string id = scene_anchor(index);
  std::string s = fmt::format(
      "<section class=\"scene {0}\" id=\"{1}\" aria-labelledby=\"{1}-h\"><h2 id=\"{1}-h\">Scene "
      "{2} {3}</h2>",
      verdict_class(scene.verdict), id, html_escape(scene.name), verdict_badge(scene.verdict));
  s += verdict_explanation(scene);
  s += timing_facts(scene);
  if (!scene.layers.empty()) {
    const SceneImages pictures = read_scene_images(scene);
    for (const std::string* problem : {&pictures.golden_problem, &pictures.new_problem})
      if (!problem->empty()) s += "<p class=\"note\">" + html_escape(*problem) + "</p>";
    for (size_t l = 0; l < scene.layers.size(); ++l) {
      const LayerResult& layer = scene.layers[l];
      const std::string layer_id = id + "-l" + std::to_string(l);
      const std::string stem = "s" + std::to_string(index) + "-" + safe_file_name(scene.name) +
                               "-l" + std::to_string(l) + "-" + safe_file_name(layer.layer);
      s += layer_section(scene, layer, images.draw_layer(pictures, layer, stem), layer_id);
    }
  }
  s += trend_charts(scene, id, trend);
  return s + "</section>";
}

}  // namespace vesper::regress
