#pragma once
// One scene's trend across runs as an inline SVG line chart: render time,
// the largest |Z| (how far from the golden) or the smallest detectable
// change (how noisy). Each run is a marker whose shape says its verdict
// (circle pass, triangle regressed, square error), so colour is not needed
// to read it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "regress/regress_result.h"
#include "regress/trend.h"

namespace vesper::regress {

enum class TrendFigure { RenderSeconds, MaxAbsZ, MinDetectableChange };

// The scene's points: those of `history` (may be null) plus the run's own
// unless the history already has its run, oldest first, at most `limit`
// (the newest).
std::vector<TrendPoint> scene_trend(const std::vector<TrendPoint>* history, const RunResult& run,
                                    std::string_view scene, size_t limit = 60);

// `points` one scene's, oldest first; `reference` a dashed horizontal line
// (e.g. the golden's render time), `id` unique in the page.
std::string trend_chart_svg(const std::vector<TrendPoint>& points, TrendFigure figure,
                            std::string_view id, std::optional<double> reference = std::nullopt);

}  // namespace vesper::regress
