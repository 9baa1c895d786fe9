// vesper regress: re-render a suite, compare each frame and layer with its
// golden without alarms for Monte Carlo noise, and report what changed
// (docs/regression.md).
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>

#include "cli/commands.h"
#include "cli/farm_setup.h"
#include "cli/progress.h"
#include "cli/regress_render.h"
#include "jobs/frame_range.h"
#include "regress/history.h"
#include "regress/load_frame.h"
#include "regress/median.h"
#include "regress/render_time.h"
#include "regress/report_html.h"
#include "regress/report_json.h"
#include "regress/suite.h"
#include "regress/verdicts.h"

namespace vesper::cli {
namespace {

namespace fs = std::filesystem;
using regress::Verdict;

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// One scene and frame: render, then write the golden or compare with it.
regress::SceneResult regress_frame(const regress::SuiteScene& scene, int frame,
                                   const std::string& label, const RegressCommandOptions& o,
                                   const RegressRenderSettings& settings,
                                   const regress::History* history) {
  const fs::path goldens(o.goldens);
  const SuiteRender render = render_suite_frame(scene, frame, label, settings);
  regress::SceneResult result;
  result.name = label;
  if (!render.error.empty()) {
    return regress::error_result(label, render.error);
  }
  if (o.update_goldens) {
    write_golden(render, goldens);
    result.reasons.push_back("golden written: " + golden_image(goldens, label).string());
    result.new_seconds = regress::median(render.seconds);
    result.new_seconds_repeats = render.seconds;
    return result;
  }
  const std::vector<std::string>* layers = scene.layers ? &*scene.layers : nullptr;
  result = regress::compare_files(label, golden_image(goldens, label), render.exr, layers,
                                  scene.thresholds);
  result.new_seconds = regress::median(render.seconds);
  result.new_seconds_repeats = render.seconds;
  if (const auto g = golden_seconds(goldens, label)) result.golden_seconds = *g;
  std::optional<double> history_seconds;
  if (history) history_seconds = history->median_seconds(label, 10);
  if (result.verdict != Verdict::Error)
    regress::judge_render_time(result, scene.thresholds, history_seconds);
  return result;
}

void print_result(const regress::SceneResult& s) {
  std::string line = std::string(regress::verdict_name(s.verdict)) + "  " + s.name;
  double weakest = 0;  // the beauty's, when it was compared
  for (const auto& l : s.layers)
    if (l.layer == "beauty") weakest = l.min_detectable_change;
  if (s.verdict == Verdict::Pass && weakest > 0) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "  (would have flagged tile changes of %.2g %% or more)",
                  100 * weakest);
    line += buf;
  }
  std::printf("%s\n", line.c_str());
  for (const std::string& r : s.reasons) std::printf("    %s\n", r.c_str());
  for (const auto& l : s.layers)
    for (const std::string& r : l.reasons) std::printf("    %s: %s\n", l.layer.c_str(), r.c_str());
}

// Every (scene, frame) of the suite, with the label its files get.
struct SuiteFrame {
  const regress::SuiteScene* scene;
  int frame;
  std::string label;
};

std::vector<SuiteFrame> suite_frames(const regress::Suite& suite) {
  std::vector<SuiteFrame> out;
  for (const regress::SuiteScene& s : suite.scenes) {
    const std::vector<int> frames = parse_frame_range(s.frames);  // load_suite checked it
    for (int f : frames)
      out.push_back({&s, f, frames.size() == 1 ? s.name : s.name + "." + std::to_string(f)});
  }
  return out;
}

// Bad input before any render: exit 2 with the reason.
std::optional<regress::Suite> check_inputs(const RegressCommandOptions& o) {
  if (o.server) {
    spdlog::error("--server: the farm mode of vesper regress is not built yet; use --local");
    return std::nullopt;
  }
  std::optional<regress::Suite> suite;
  try {
    suite = regress::load_suite(o.suite);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return std::nullopt;
  }
  std::error_code ec;
  if (o.update_goldens) fs::create_directories(o.goldens, ec);
  if (!fs::is_directory(o.goldens)) {
    spdlog::error("--goldens {}: not a folder{}", o.goldens,
                  o.update_goldens ? " (and it cannot be created)"
                                   : " (write the goldens first with --update-goldens)");
    return std::nullopt;
  }
  return suite;
}

// report.json, index.html and the history, as asked.
int write_outputs(const regress::RunResult& run, const RegressCommandOptions& o,
                  regress::History* history) {
  try {
    if (history) history->record(run);
    if (o.report) {
      fs::create_directories(*o.report);
      regress::write_report_json(run, fs::path(*o.report) / "report.json");
      const std::vector<regress::TrendPoint> trends =
          history ? history->recent_trends(60) : std::vector<regress::TrendPoint>{};
      regress::write_report_html(run, history ? &trends : nullptr, *o.report);
      if (!o.quiet) spdlog::info("report: {}", (fs::path(*o.report) / "index.html").string());
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  return 0;
}

}  // namespace

int run_regress(const RegressCommandOptions& o) {
  const std::optional<regress::Suite> suite = check_inputs(o);
  if (!suite) return 2;
  std::unique_ptr<regress::History> history;
  try {
    if (o.history) history = std::make_unique<regress::History>(*o.history);
  } catch (const std::exception& e) {
    spdlog::error("--history {}: {}", *o.history, e.what());
    return 2;
  }
  RegressRenderSettings settings;
  settings.renderer = o.renderer ? fs::path(*o.renderer) : self_executable();
  settings.seed = o.seed;
  settings.threads = o.threads;
  settings.repeats = std::max(1, o.repeats);
  // The new renders stay beside the report (its pictures come from them), else in a temp folder.
  const bool keep = o.report.has_value();
  settings.out_dir =
      keep ? fs::path(*o.report) / "renders"
           : fs::temp_directory_path() / ("vesper-regress-" + std::to_string(::getpid()));
  fs::create_directories(settings.out_dir);

  regress::RunResult run;
  run.suite = o.suite;
  run.started_at = utc_now();
  run.renderer_version = VESPER_VERSION;
  const std::vector<SuiteFrame> frames = suite_frames(*suite);
  Progress progress("regress");
  for (size_t i = 0; i < frames.size(); ++i) {
    if (!o.quiet) progress.update(i, frames.size());
    const SuiteFrame& f = frames[i];
    regress::SceneResult r = regress_frame(*f.scene, f.frame, f.label, o, settings, history.get());
    run.scenes.push_back(std::move(r));
  }
  if (!o.quiet) progress.update(frames.size(), frames.size());
  progress.finish();
  regress::summarize_run(run);
  for (const auto& s : run.scenes) print_result(s);
  const int written = write_outputs(run, o, history.get());
  if (!keep) fs::remove_all(settings.out_dir);
  if (written != 0) return written;
  std::printf("%s: %s\n", o.suite.c_str(), regress::verdict_name(run.verdict));
  return run.verdict == Verdict::Pass ? 0 : 1;
}

}  // namespace vesper::cli
