#include "measure/bench_table.h"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

namespace vesper::measure {
namespace {

using Row = std::vector<std::string>;

std::string seconds_text(double s) { return fmt::format("{:.3g} s", s); }

std::string target_text(double t) { return fmt::format("{:g}", t); }

std::vector<Row> renderer_rows(const BenchReport& report) {
  std::vector<Row> rows;
  Row head = {"scene", "kind", "renderer", "reference", "noise floor"};
  for (double t : report.targets) head.push_back("time to " + target_text(t));
  rows.push_back(head);
  for (const SceneResult& s : report.scenes) {
    if (s.skipped) {
      Row r = {s.name, s.kind, "-", "skipped (below)", "-"};
      r.resize(head.size(), "-");
      rows.push_back(r);
      continue;
    }
    for (const RendererRun& run : s.runs) {
      Row r = {s.name, s.kind, run.renderer,
               run.error.empty() ? (run.reference_cached ? "cache hit" : "rendered") : "failed",
               run.error.empty() ? fmt::format("{:.2g}", run.noise_floor) : "-"};
      for (const TargetTime& t : run.times)
        r.push_back(format_time_to_error(t.time) +
                    (reference_limited(run.noise_floor, t.target) ? " !" : ""));
      r.resize(head.size(), "-");
      rows.push_back(r);
    }
  }
  return rows;
}

std::string ratio_text(const RatioAtTarget& r) {
  if (!r.ratio) return "-";
  return fmt::format("{}{:.2f}x ({} {:.1f}x)", r.approximate ? "~" : "", *r.ratio,
                     *r.goal_met ? "met <=" : "NOT met <=", r.goal);
}

std::string agreement_text(const PeerComparison& c) {
  if (!c.agreement) return "-";
  const ReferenceAgreement& a = *c.agreement;
  std::string s = fmt::format("mean {:.3f}, blocks p5 {:.3f} p95 {:.3f} (min {:.3f}, max {:.3f})",
                              a.mean_ratio, a.block_p05, a.block_p95, a.block_min, a.block_max);
  if (a.flagged) s += " FLAGGED";
  return s;
}

std::vector<Row> peer_rows(const BenchReport& report) {
  std::vector<Row> rows;
  Row head = {"scene", "kind", "vesper / peer"};
  for (double t : report.targets) head.push_back("ratio at " + target_text(t));
  head.push_back("references (vesper / peer)");
  rows.push_back(head);
  for (const SceneResult& s : report.scenes)
    for (const PeerComparison& c : s.comparisons) {
      Row r = {s.name, s.kind, "vesper / " + c.peer};
      for (const RatioAtTarget& ratio : c.ratios) r.push_back(ratio_text(ratio));
      r.resize(head.size() - 1, "-");
      r.push_back(agreement_text(c));
      rows.push_back(r);
    }
  return rows.size() > 1 ? rows : std::vector<Row>{};
}

std::string markdown(const std::vector<Row>& rows) {
  std::string out;
  for (size_t i = 0; i < rows.size(); ++i) {
    out += "|";
    for (const std::string& cell : rows[i]) out += " " + cell + " |";
    out += "\n";
    if (i == 0) {
      out += "|";
      for (size_t c = 0; c < rows[0].size(); ++c) out += "---|";
      out += "\n";
    }
  }
  return out;
}

std::string aligned(const std::vector<Row>& rows) {
  std::vector<size_t> width;
  for (const Row& r : rows)
    for (size_t c = 0; c < r.size(); ++c) {
      if (width.size() <= c) width.push_back(0);
      width[c] = std::max(width[c], r[c].size());
    }
  std::string out;
  for (const Row& r : rows) {
    std::string line;
    for (size_t c = 0; c < r.size(); ++c)
      line += fmt::format("{:<{}}", r[c], c + 1 < r.size() ? width[c] + 2 : 0);
    out += line + "\n";
  }
  return out;
}

std::string legend() {
  return "Times are render seconds, read off the log-log curve of relMSE against render time. "
         "`~t*`: the curve never reached the target, extrapolated with slope -1; `< t`: already "
         "the first measurement was below the target. Ratios marked `~` use such a time. `!`: the "
         "reference's noise floor is at least half the target, so that time is limited by the "
         "reference (raise reference_spp).\n";
}

// Why scenes were skipped, one line each, after the table (too long for a cell).
std::string notes(const BenchReport& report, const std::string& bullet) {
  std::string out;
  for (const SceneResult& s : report.scenes)
    if (s.skipped) out += bullet + s.name + ": " + s.note + "\n";
  return out.empty() ? out : "\n" + out;
}

}  // namespace

std::string format_time_to_error(const TimeToError& t) {
  switch (t.estimate) {
    case TimeEstimate::Interpolated:
      return seconds_text(t.seconds);
    case TimeEstimate::Extrapolated:
      return "~" + seconds_text(t.seconds) + "*";
    case TimeEstimate::BelowFirst:
      return "< " + seconds_text(t.seconds);
    case TimeEstimate::None:
      break;
  }
  return "-";
}

std::string bench_table_markdown(const BenchReport& report) {
  std::string out = "# vesper bench\n\n" + markdown(renderer_rows(report)) + notes(report, "- ");
  const std::vector<Row> peers = peer_rows(report);
  if (!peers.empty()) out += "\n" + markdown(peers);
  return out + "\n" + legend();
}

std::string bench_table_text(const BenchReport& report) {
  std::string out = aligned(renderer_rows(report)) + notes(report, "");
  const std::vector<Row> peers = peer_rows(report);
  if (!peers.empty()) out += "\n" + aligned(peers);
  return out;
}

}  // namespace vesper::measure
