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
#include "cli/farm_client.h"
#include "cli/farm_setup.h"
#include "cli/progress.h"
#include "cli/regress_farm.h"
#include "cli/regress_render.h"
#include "protocol/paths.h"
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

// Why a farm run's render times are shown and not judged (docs/regression.md).
constexpr const char* kFarmTimeNote =
    "shown, not judged: farm workers differ in hardware and load, and a farm task renders once "
    "(identical tasks are reused), so there are no repeated timings to take the fastest of";

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// Render time: judged locally against a local golden (its sidecar's wall
// time); for a farm render both EXRs' own render times are shown, not judged
// (docs/regression.md, "Render time on the farm").
void judge_time(regress::SceneResult& result, const SuiteRender& render,
                const regress::SuiteScene& scene, const fs::path& goldens,
                const regress::History* history) {
  result.new_seconds = regress::median(render.seconds);
  result.new_seconds_repeats = render.seconds;
  if (render.on_farm) {  // like with like: the golden EXR's own render time
    result.golden_seconds = exr_render_seconds(golden_image(goldens, render.label)).value_or(0);
    return;
  }
  const std::optional<GoldenTime> golden = golden_seconds(goldens, render.label);
  if (golden) result.golden_seconds = golden->seconds;
  if (result.verdict == Verdict::Error || !golden) return;
  if (golden->on_farm) {
    spdlog::warn("{}: render time not judged: the golden was timed on the farm", render.label);
    return;
  }
  std::optional<double> history_seconds;
  if (history) history_seconds = history->median_seconds(render.label, 10);
  regress::judge_render_time(result, scene.thresholds, history_seconds);
}

// One scene and frame, rendered: write the golden or compare with it.
regress::SceneResult judge_frame(const SuiteFrame& f, const SuiteRender& render,
                                 const RegressCommandOptions& o, const regress::History* history) {
  const fs::path goldens(o.goldens);
  if (!render.error.empty()) {
    regress::SceneResult error = regress::error_result(f.label, render.error);
    error.reused = render.reused;
    return error;
  }
  regress::SceneResult result;
  if (o.update_goldens) {
    write_golden(render, goldens);
    result.name = f.label;
    result.reasons.push_back("golden written: " + golden_image(goldens, f.label).string());
    result.new_seconds = regress::median(render.seconds);
    result.new_seconds_repeats = render.seconds;
  } else {
    const std::vector<std::string>* layers = f.scene->layers ? &*f.scene->layers : nullptr;
    result = regress::compare_files(f.label, golden_image(goldens, f.label), render.exr, layers,
                                    f.scene->thresholds);
    judge_time(result, render, *f.scene, goldens, history);
  }
  result.reused = render.reused;
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
  if (s.reused) line += "  (reused: not re-rendered)";
  std::printf("%s\n", line.c_str());
  for (const std::string& r : s.reasons) std::printf("    %s\n", r.c_str());
  for (const auto& l : s.layers)
    for (const std::string& r : l.reasons) std::printf("    %s: %s\n", l.layer.c_str(), r.c_str());
}

// Bad input before any render: exit 2 with the reason.
std::optional<regress::Suite> check_inputs(const RegressCommandOptions& o) {
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

// The farm at --server, checked before anything is submitted: nullptr (exit
// 2) when it does not answer or refuses the token.
std::unique_ptr<FarmClient> connect_farm(const RegressCommandOptions& o) {
  try {
    const FarmSettings settings = load_farm_settings(o.farm.config);
    const std::string url = resolve_server_url(settings, o.farm.server);
    // First whether it answers at all (no token needed), then whether it takes ours.
    FarmClient(url, "").get_text(std::string(protocol::paths::kHealthz));
    auto client = std::make_unique<FarmClient>(
        url, resolve_token(settings, url, o.farm.token, TokenRole::Submitter));
    client->get_json(std::string(protocol::paths::kWorkers));  // answers, takes the token
    return client;
  } catch (const std::exception& e) {
    spdlog::error("--server {}: {}", o.farm.server.value_or(""), e.what());
    return nullptr;
  }
}

// --local: each frame rendered here (repeated for the timing), then judged.
std::vector<regress::SceneResult> regress_locally(const std::vector<SuiteFrame>& frames,
                                                  const RegressCommandOptions& o,
                                                  const fs::path& out_dir,
                                                  const regress::History* history) {
  RegressRenderSettings settings;
  settings.renderer = o.renderer ? fs::path(*o.renderer) : self_executable();
  settings.seed = o.seed;
  settings.threads = o.threads;
  settings.repeats = std::max(1, o.repeats);
  settings.out_dir = out_dir;
  std::vector<regress::SceneResult> results;
  Progress progress("regress");
  for (size_t i = 0; i < frames.size(); ++i) {
    if (!o.quiet) progress.update(i, frames.size());
    const SuiteFrame& f = frames[i];
    const SuiteRender render = render_suite_frame(*f.scene, f.frame, f.label, settings);
    results.push_back(judge_frame(f, render, o, history));
  }
  if (!o.quiet) progress.update(frames.size(), frames.size());
  progress.finish();
  return results;
}

// --server: the suite rendered on the farm as one batch, then each frame judged.
std::vector<regress::SceneResult> regress_on_farm(FarmClient& client, const regress::Suite& suite,
                                                  const std::vector<SuiteFrame>& frames,
                                                  const RegressCommandOptions& o,
                                                  const fs::path& out_dir,
                                                  const regress::History* history) {
  const FarmBatchSettings settings{out_dir, o.seed, !o.quiet};
  const std::vector<SuiteRender> renders = render_suite_on_farm(client, suite, frames, settings);
  std::vector<regress::SceneResult> results;
  for (size_t i = 0; i < frames.size(); ++i)
    results.push_back(judge_frame(frames[i], renders[i], o, history));
  return results;
}

}  // namespace

int run_regress(const RegressCommandOptions& o) {
  const std::optional<regress::Suite> suite = check_inputs(o);
  if (!suite) return 2;
  std::unique_ptr<FarmClient> farm;
  if (o.farm.server && !(farm = connect_farm(o))) return 2;
  std::unique_ptr<regress::History> history;
  try {
    if (o.history) history = std::make_unique<regress::History>(*o.history);
  } catch (const std::exception& e) {
    spdlog::error("--history {}: {}", *o.history, e.what());
    return 2;
  }
  // The new renders stay beside the report (its pictures come from them), else in a temp folder.
  const bool keep = o.report.has_value();
  const fs::path out_dir =
      keep ? fs::path(*o.report) / "renders"
           : fs::temp_directory_path() / ("vesper-regress-" + std::to_string(::getpid()));
  fs::create_directories(out_dir);

  regress::RunResult run;
  run.suite = o.suite;
  run.started_at = utc_now();
  run.renderer_version = VESPER_VERSION;
  const std::vector<SuiteFrame> frames = suite_frames(*suite);
  if (farm) {
    run.server = farm->url();
    run.render_time_note = kFarmTimeNote;
    run.scenes = regress_on_farm(*farm, *suite, frames, o, out_dir, history.get());
  } else {
    run.scenes = regress_locally(frames, o, out_dir, history.get());
  }
  regress::summarize_run(run);
  for (const auto& s : run.scenes) print_result(s);
  if (!run.render_time_note.empty())
    std::printf("render times: %s\n", run.render_time_note.c_str());
  const int written = write_outputs(run, o, history.get());
  if (!keep) fs::remove_all(out_dir);
  if (written != 0) return written;
  std::printf("%s: %s\n", o.suite.c_str(), regress::verdict_name(run.verdict));
  return run.verdict == Verdict::Pass ? 0 : 1;
}

}  // namespace vesper::cli
