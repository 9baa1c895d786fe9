#include "measure/bench_report.h"

#include <cmath>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "measure/bench_plot.h"
#include "measure/bench_table.h"

namespace vesper::measure {
namespace {

using nlohmann::json;

// JSON has no infinity or NaN: such a value is null.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json time_json(const TargetTime& t, double noise_floor) {
  return {
      {"target", t.target},
      {"reference_limited", reference_limited(noise_floor, t.target)},
      {"seconds", t.time.estimate == TimeEstimate::None ? json(nullptr) : number(t.time.seconds)},
      {"estimate", time_estimate_name(t.time.estimate)}};
}

json run_json(const RendererRun& run) {
  json curve = json::array(), times = json::array();
  for (const Measurement& m : run.curve)
    curve.push_back({{"spp", m.spp},
                     {"render_seconds", number(m.render_seconds)},
                     {"wall_seconds", number(m.wall_seconds)},
                     {"relmse", number(m.relmse)}});
  for (const TargetTime& t : run.times) times.push_back(time_json(t, run.noise_floor));
  json j = {{"renderer", run.renderer},
            {"cache_key", run.cache_key},
            {"reference",
             {{"file", run.reference_file},
              {"cache_hit", run.reference_cached},
              {"render_seconds", number(run.reference_seconds)},
              {"noise_floor", number(run.noise_floor)}}},
            {"measurements", curve},
            {"time_to_error", times}};
  if (!run.error.empty()) j["error"] = run.error;
  return j;
}

json agreement_json(const ReferenceAgreement& a) {
  return {{"mean_ratio", number(a.mean_ratio)},
          {"blocks", a.blocks},
          {"block_min", number(a.block_min)},
          {"block_p05", number(a.block_p05)},
          {"block_p95", number(a.block_p95)},
          {"block_max", number(a.block_max)},
          {"flagged", a.flagged},
          {"reasons", a.reasons}};
}

json comparison_json(const PeerComparison& c) {
  json ratios = json::array();
  for (const RatioAtTarget& r : c.ratios)
    ratios.push_back({{"target", r.target},
                      {"ratio", r.ratio ? number(*r.ratio) : json(nullptr)},
                      {"approximate", r.approximate},
                      {"goal", r.goal},
                      {"goal_met", r.goal_met ? json(*r.goal_met) : json(nullptr)}});
  return {{"peer", c.peer},
          {"equal_error_ratios", ratios},
          {"references", c.agreement ? agreement_json(*c.agreement) : json(nullptr)}};
}

json scene_json(const SceneResult& s) {
  json j = {{"name", s.name},        {"kind", s.kind},
            {"scene", s.scene_path}, {"scene_hash", s.scene_hash},
            {"width", s.width},      {"height", s.height},
            {"spp", s.spp_ladder},   {"reference_spp", s.reference_spp},
            {"skipped", s.skipped}};
  if (s.skipped) j["note"] = s.note;
  j["renderers"] = json::array();
  for (const RendererRun& r : s.runs) j["renderers"].push_back(run_json(r));
  j["comparisons"] = json::array();
  for (const PeerComparison& c : s.comparisons) j["comparisons"].push_back(comparison_json(c));
  return j;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

nlohmann::json bench_json(const BenchReport& report) {
  json scenes = json::array();
  for (const SceneResult& s : report.scenes) scenes.push_back(scene_json(s));
  return {{"format", kBenchReportFormat},
          {"renderer_version", VESPER_VERSION},
          {"scenes_file", report.set_path},
          {"quick", report.quick},
          {"threads", report.threads},
          {"seed", std::to_string(report.seed)},
          {"targets", report.targets},
          {"renderers", report.renderers},
          {"total_seconds", number(report.total_seconds)},
          {"scenes", scenes}};
}

std::string bench_csv(const BenchReport& report) {
  std::string out =
      "scene,kind,renderer,spp,render_seconds,wall_seconds,relmse,reference_noise_floor,"
      "reference_cached\n";
  for (const SceneResult& s : report.scenes)
    for (const RendererRun& r : s.runs)
      for (const Measurement& m : r.curve)
        out += fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{}\n", csv_field(s.name),
                           s.kind, csv_field(r.renderer), m.spp, m.render_seconds, m.wall_seconds,
                           m.relmse, r.noise_floor, r.reference_cached ? "true" : "false");
  return out;
}

std::vector<std::filesystem::path> write_bench_outputs(const BenchReport& report,
                                                       const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> written;
  auto put = [&](const std::string& name, const std::string& bytes) {
    write_file_atomically(dir / name, bytes);
    written.push_back(dir / name);
  };
  for (const SceneResult& s : report.scenes) {
    if (s.skipped || s.runs.empty()) continue;
    const std::filesystem::path png = dir / ("plot-" + s.name + ".png");
    write_plot_png(s, report.targets, png);
    written.push_back(png);
  }
  put("bench.csv", bench_csv(report));
  put("table.md", bench_table_markdown(report));
  put("bench.json", bench_json(report).dump(2) + "\n");  // last: its presence means complete
  return written;
}

}  // namespace vesper::measure
