#pragma once
// The HTML report's page in pieces; report_html.cpp puts them together.
// Every piece is a fragment of escaped HTML.
#include <string>
#include <vector>

#include "regress/regress_result.h"
#include "regress/report_images.h"
#include "regress/trend.h"

namespace vesper::regress {

// The verdict as symbol and word ("✗ REGRESSED"), coloured by its class:
// readable without colour. `css` is "verdict" (a badge) or "overall".
std::string verdict_badge(Verdict v, const char* css = "verdict");
std::string verdict_class(Verdict v);  // "v-pass", "v-regressed", "v-error"

// "1.2 s &rarr; 1.25 s (&times;1.04)" (golden, new, ratio; "unknown" for a
// time not measured), or "reused: not re-rendered".
std::string render_time_text(const SceneResult& scene);

// "scene-<index>": the scene section's id, linked from the summary table.
std::string scene_anchor(size_t index);

// One scene: verdict, reasons (an error's in an alert box), how strong a pass
// was, timing, then each layer and the trend charts across runs.
std::string scene_section(const SceneResult& scene, size_t index, const ReportImages& images,
                          const std::vector<TrendPoint>& trend);

// One layer: verdict, reasons and figures, the four pictures side by side
// (worst regions outlined on the new render), the regions as a table, the
// histograms overlaid. `id` unique in the page, file-name safe.
std::string layer_section(const SceneResult& scene, const LayerResult& layer,
                          const LayerPictures& pictures, const std::string& id);

}  // namespace vesper::regress
