#pragma once
// `vesper regress --report DIR`'s self-contained HTML page: DIR/index.html
// and its pictures under DIR/img/. No network at all (no CDN, web font or
// script; inline CSS and SVG charts), so it opens from a file, an artifact
// store or a mail attachment's folder alike. See docs/regression.md, "Report".
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "regress/regress_result.h"
#include "regress/trend.h"

namespace vesper::regress {

struct ReportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes DIR/index.html for `run` (creating DIR): the overall verdict, a
// table of scenes, per scene and layer the golden / new / difference /
// significance pictures, regions, histograms, and trend charts from
// `trends` (earlier runs' points from the history, any scenes and order;
// may be null; the run's own points are added unless already there).
// The pictures go to a new DIR/img/run-* folder and the page replaces the
// old one by rename, so a crash leaves the previous report whole; the
// previous run's picture folder is removed after. Throws ReportError when
// DIR or a file cannot be written. A picture that cannot be drawn (a missing
// or unreadable EXR) is not an error: the page says why it is missing.
void write_report_html(const RunResult& run, const std::vector<TrendPoint>* trends,
                       const std::filesystem::path& dir);

}  // namespace vesper::regress
