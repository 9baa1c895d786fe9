// One layer's part of the HTML report (report_sections.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "regress/colour_ramp.h"
#include "regress/histogram_chart.h"
#include "regress/html_text.h"
#include "regress/report_sections.h"
#include "regress/svg_plot.h"

namespace vesper::regress {

namespace {

// A horizontal colour bar with its two end labels (and an optional extra
// swatch, e.g. "NaN/Inf"), as a small SVG under a picture.
std::string ramp_legend(const std::string& id, std::span<const RampStop> ramp,
                        const std::string& title, const std::string& low, const std::string& high,
                        const std::string& extra_colour = "", const std::string& extra_label = "") {
  std::string stops;
  for (const RampStop& s : ramp)
    stops += fmt::format("<stop offset=\"{}\" stop-color=\"{}\"/>", svg_number(s.t),
                         css_colour(s.colour));
  std::string s = fmt::format(
      "<svg class=\"legend-bar\" viewBox=\"0 0 300 34\" width=\"300\" height=\"34\" role=\"img\" "
      "aria-label=\"{0}: from {1} to {2}{3}\"><defs><linearGradient id=\"{4}\">{5}"
      "</linearGradient></defs><rect x=\"0\" y=\"2\" width=\"180\" height=\"12\" "
      "fill=\"url(#{4})\" "
      "stroke=\"#8a909a\"/><text x=\"0\" y=\"28\">{1}</text><text x=\"180\" y=\"28\" "
      "text-anchor=\"end\">{2}</text>",
      html_escape(title), html_escape(low), html_escape(high),
      extra_label.empty() ? "" : "; " + html_escape(extra_label), html_escape(id), stops);
  if (!extra_label.empty())
    s += fmt::format(
        "<rect x=\"190\" y=\"2\" width=\"12\" height=\"12\" fill=\"{}\" stroke=\"#8a909a\"/>"
        "<text x=\"206\" y=\"12\">{}</text>",
        extra_colour, html_escape(extra_label));
  return s + "</svg>";
}

// The worst regions as numbered outlines over the new render (pixel
// coordinates: the SVG stretches with the picture).
std::string region_overlay(const LayerResult& layer, int width, int height) {
  if (layer.worst.empty() || width <= 0 || height <= 0) return "";
  std::string s =
      fmt::format("<svg viewBox=\"0 0 {} {}\" preserveAspectRatio=\"none\" aria-hidden=\"true\">",
                  width, height);
  // Labels scale with the picture: readable on a 64 px test render shown
  // large and on a 2K frame shown small alike.
  const double font = std::max(width, height) / 32.0;
  for (size_t i = 0; i < layer.worst.size(); ++i) {
    const Region& r = layer.worst[i];
    const std::string box =
        fmt::format("x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"", r.x, r.y, r.width, r.height);
    s += fmt::format("<rect class=\"region-outer\" {0}/><rect class=\"region-inner\" {0}/>", box);
    s += fmt::format("<text class=\"region-label\" x=\"{}\" y=\"{}\" font-size=\"{}\">{}</text>",
                     svg_number(r.x + font * 0.3), svg_number(r.y + font * 1.05), svg_number(font),
                     i + 1);
  }
  return s + "</svg>";
}

// A picture with its caption (and an overlay and a legend), or a dashed
// box that says why it is missing.
std::string picture(const std::string& src, const std::string& alt, const std::string& caption,
                    const LayerPictures& p, const std::string& overlay = "",
                    const std::string& legend = "") {
  if (src.empty())
    return fmt::format(
        "<figure><div class=\"missing\">not available</div><figcaption>{}"
        "</figcaption></figure>",
        html_escape(caption));
  return fmt::format(
      "<figure><div class=\"frame\"><img src=\"{}\" alt=\"{}\" width=\"{}\" height=\"{}\">{}</div>"
      "<figcaption>{}</figcaption>{}</figure>",
      html_escape(src), html_escape(alt), p.width, p.height, overlay, html_escape(caption), legend);
}

std::string figures_line(const LayerResult& layer) {
  std::string power = layer.has_variance
                          ? "could have detected changes &ge; " +
                                html_escape(format_percent(layer.min_detectable_change))
                          : "no variance channels: compared without a noise model";
  return fmt::format(
      "<p class=\"figures\">{} of {} tiles significant, largest |Z| {}; {}; histogram distance "
      "{} stops; NaN/Inf pixels {} in the golden, {} in the new render.</p>",
      layer.significant_tiles, layer.tiles, html_escape(format_figure(layer.max_abs_z, 3)), power,
      html_escape(format_figure(layer.histogram_distance, 3)), layer.golden_nonfinite,
      layer.new_nonfinite);
}

std::string regions_table(const LayerResult& layer, const std::string& layer_name) {
  if (layer.worst.empty()) return "";
  std::string s = fmt::format(
      "<table><caption>Worst regions of {} (numbered as outlined on the new render)</caption>"
      "<thead><tr><th scope=\"col\">#</th><th scope=\"col\">pixels (x, y, w &times; h)</th>"
      "<th scope=\"col\">Z</th><th scope=\"col\">p (uncorrected)</th><th scope=\"col\">mean "
      "golden &rarr; new</th><th scope=\"col\">change</th></tr></thead><tbody>",
      html_escape(layer_name));
  for (size_t i = 0; i < layer.worst.size(); ++i) {
    const Region& r = layer.worst[i];
    s += fmt::format(
        "<tr><td class=\"num\">{}</td><td class=\"num\">{}, {}, {} &times; {}</td><td "
        "class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{} &rarr; {}</td><td "
        "class=\"num\">{} ({})</td></tr>",
        i + 1, r.x, r.y, r.width, r.height, html_escape(format_figure(r.z, 3)),
        html_escape(format_figure(r.p_value, 2)), html_escape(format_figure(r.golden_mean, 3)),
        html_escape(format_figure(r.new_mean, 3)),
        html_escape(format_percent(r.relative_change, true)),
        r.relative_change < 0 ? "darker" : "brighter");
  }
  return s + "</tbody></table>";
}

std::string pictures_grid(const SceneResult& scene, const LayerResult& layer,
                          const LayerPictures& p, const std::string& id) {
  const std::string what = scene.name + ", layer " + layer.layer;
  const std::string heat_legend =
      ramp_legend(id + "-heat", viridis_stops(), "difference heat map", "0",
                  format_figure(p.difference_top, 3) + " or more", "#ff00ff", "NaN/Inf");
  const std::string sig_legend =
      ramp_legend(id + "-sig", diverging_stops(), "significance map",
                  "Z -" + format_figure(p.z_scale, 2) + " darker",
                  "Z +" + format_figure(p.z_scale, 2) + " brighter", "#7a7a7a", "not significant");
  std::string s = "<div class=\"pictures\">";
  s += picture(p.golden, "Golden render of " + what, "Golden", p);
  s += picture(p.fresh,
               "New render of " + what + (layer.worst.empty() ? "" : ", worst regions outlined"),
               layer.worst.empty() ? "New" : "New, worst regions outlined and numbered", p,
               region_overlay(layer, p.width, p.height));
  s += picture(p.difference, "Difference heat map of " + what,
               "Difference: |new - golden| luminance (" + std::to_string(p.difference_nonfinite) +
                   " NaN/Inf pixels)",
               p, "", heat_legend);
  s += picture(p.significance,
               "Significance map of " + what + ": " + std::to_string(layer.significant_tiles) +
                   " significant tiles",
               "Significance: tile Z after correction", p, "", sig_legend);
  return s + "</div>";
}

}  // namespace

std::string layer_section(const SceneResult& scene, const LayerResult& layer,
                          const LayerPictures& p, const std::string& id) {
  std::string s = fmt::format(
      "<section class=\"layer {0}\" aria-labelledby=\"{1}-h\"><h3 id=\"{1}-h\">Layer {2} {3}</h3>",
      verdict_class(layer.verdict), html_escape(id), html_escape(layer.layer),
      verdict_badge(layer.verdict));
  if (!layer.reasons.empty()) {
    s += "<ul class=\"reasons\">";
    for (const std::string& r : layer.reasons) s += "<li>" + html_escape(r) + "</li>";
    s += "</ul>";
  }
  s += figures_line(layer);
  s += pictures_grid(scene, layer, p, id);
  for (const std::string& problem : p.problems)
    s += "<p class=\"note\">" + html_escape(problem) + "</p>";
  s += regions_table(layer, layer.layer);
  if (p.golden_histogram && p.new_histogram)
    s += "<div class=\"charts\">" +
         histogram_overlay_svg(*p.golden_histogram, *p.new_histogram, id + "-hist",
                               "Luminosity histograms of " + layer.layer + ": golden vs new",
                               layer.histogram_distance) +
         "</div>";
  return s + "</section>";
}

}  // namespace vesper::regress
