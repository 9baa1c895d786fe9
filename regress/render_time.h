#pragma once
// Render time against the golden's (and the history's): a slowdown beyond
// thresholds.max_slowdown regresses. Timings only get slower by accident
// (other load, cold caches), never faster, so the fastest of the repeated
// timings is the one judged; the median is what the report shows.
#include <optional>

#include "regress/regress_result.h"
#include "regress/suite.h"

namespace vesper::regress {

// Uses scene.golden_seconds and scene.new_seconds_repeats (or new_seconds
// when there are none); sets new_seconds to the median of the repeats. With
// `history_seconds` (the median of the scene's recent runs, history.h) a
// slowdown must show against both references. Reused results (nothing was
// rendered) and missing timings are not judged. Adds a reason and regresses.
void judge_render_time(SceneResult& scene, const Thresholds& thresholds,
                       std::optional<double> history_seconds = std::nullopt);

}  // namespace vesper::regress
