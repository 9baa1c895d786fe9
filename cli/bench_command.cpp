// vesper bench: time against error on the benchmark set (docs/bench.md).
// The measuring is measure/'s (bench_runner.h); here: flags, the renderers,
// the progress bar, the output files and the exit code.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>

#include "cli/commands.h"
#include "cli/progress.h"
#include "measure/bench_report.h"
#include "measure/bench_runner.h"
#include "measure/bench_set.h"
#include "measure/bench_table.h"
#include "measure/cycles_renderer.h"
#include "measure/vesper_renderer.h"

namespace vesper::cli {
namespace {

namespace fs = std::filesystem;
using measure::BenchRenderer;

constexpr int kRenderFailed = 1, kBadInput = 2;
constexpr const char* kPeers = "cycles";  // the accepted --compare values

// $XDG_CACHE_HOME/vesper/bench-refs, else ~/.cache/vesper/bench-refs: shared
// by every -o, so references survive between runs and output folders.
fs::path default_refs_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "vesper/bench-refs";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache/vesper/bench-refs";
  return fs::temp_directory_path() / "vesper-bench-refs";
}

// The current render's bar: the runner names each render as it begins; the
// renderer's per-tile callback fills it.
class BenchProgress {
 public:
  void begin(const std::string& label) {
    std::lock_guard lock(mutex_);
    bar_ = std::make_unique<Progress>(label);
  }
  void update(size_t done, size_t total) {
    std::lock_guard lock(mutex_);
    if (bar_) bar_->update(done, total);
  }
  void end() {
    std::lock_guard lock(mutex_);
    if (bar_) bar_->finish();
    bar_.reset();
  }

 private:
  std::mutex mutex_;
  std::unique_ptr<Progress> bar_;
};

// bench/cycles/vesper_to_cycles.py: beside the working folder's bench/ (run
// from the repository root, as --scenes' default), else the source tree the
// executable was built in (build/cli/vesper -> ../../bench).
std::optional<fs::path> find_cycles_script() {
  const fs::path rel = "bench/cycles/vesper_to_cycles.py";
  std::vector<fs::path> candidates{fs::current_path() / rel};
  std::error_code ec;
  if (const fs::path exe = fs::read_symlink("/proc/self/exe", ec); !ec)
    candidates.push_back(exe.parent_path() / "../.." / rel);
  for (const fs::path& c : candidates)
    if (fs::is_regular_file(c, ec)) return fs::weakly_canonical(c, ec);
  return std::nullopt;
}

// The peer named by --compare, or an exit code when there is none to run.
std::optional<int> add_peer(const std::string& name, const fs::path& out, BenchProgress& progress,
                            std::vector<BenchRenderer>& renderers) {
  if (name != "cycles") {
    spdlog::error("--compare {}: unknown renderer (accepted: {})", name, kPeers);
    return kBadInput;
  }
  const auto script = find_cycles_script();
  if (!script) {
    spdlog::error(
        "--compare cycles: bench/cycles/vesper_to_cycles.py not found in {} or beside "
        "the vesper executable's source tree; run vesper bench from the repository root",
        fs::current_path().string());
    return kBadInput;
  }
  try {
    renderers.push_back(measure::cycles_renderer(
        {.script = script->string(),
         .work_dir = (out / "cycles-work").string(),
         .on_progress = [&progress](size_t d, size_t t) { progress.update(d, t); }}));
  } catch (const std::exception& e) {
    spdlog::error("--compare cycles: {}", e.what());
    return kBadInput;
  }
  return std::nullopt;
}

// -o must be a folder we can create or reuse.
bool check_output_dir(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    spdlog::error("-o {}: exists and is not a folder", dir.string());
    return false;
  }
  fs::create_directories(dir, ec);
  if (ec) {
    spdlog::error("-o {}: cannot create the folder: {}", dir.string(), ec.message());
    return false;
  }
  return true;
}

measure::RunnerEvents events_for(BenchProgress& progress) {
  measure::RunnerEvents ev;
  ev.render_begins = [&progress](const std::string& label) { progress.begin(label); };
  ev.render_ends = [&progress] { progress.end(); };
  ev.warn = [](const std::string& m) { spdlog::warn("{}", m); };
  ev.info = [](const std::string& m) { spdlog::info("{}", m); };
  return ev;
}

int report_results(const measure::BenchReport& report, const fs::path& out, bool quiet) {
  try {
    const auto files = measure::write_bench_outputs(report, out);
    if (!quiet)
      for (const fs::path& f : files) spdlog::info("wrote {}", f.string());
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kRenderFailed;
  }
  std::fputs(measure::bench_table_text(report).c_str(), stdout);
  std::fflush(stdout);
  if (!quiet) spdlog::info("bench took {}", format_seconds(report.total_seconds));
  return report.any_error() ? kRenderFailed : 0;
}

}  // namespace

int run_bench(const BenchCommandOptions& o) {
  BenchProgress progress;
  measure::VesperRendererOptions vo;
  vo.on_progress = [&progress](size_t d, size_t t) { progress.update(d, t); };
  std::vector<BenchRenderer> renderers{measure::vesper_renderer(vo)};
  if (o.compare)
    if (const auto code = add_peer(*o.compare, o.output, progress, renderers)) return *code;
  measure::BenchSet set;
  try {
    set = measure::load_bench_set(o.scenes);
  } catch (const measure::BenchSetError& e) {
    spdlog::error("{}", e.what());
    return kBadInput;
  }
  if (!check_output_dir(o.output)) return kBadInput;
  measure::RunnerOptions ro;
  ro.refs_dir = o.refs ? fs::path(*o.refs) : default_refs_dir();
  ro.quick = o.quick;
  ro.threads = o.threads.value_or(0);
  ro.seed = o.seed;
  if (!o.quiet) spdlog::info("references in {}", ro.refs_dir.string());
  measure::BenchReport report;
  try {
    report = measure::run_bench(set, renderers, ro, events_for(progress));
  } catch (const measure::BenchSceneError& e) {
    spdlog::error("{}", e.what());
    return kBadInput;
  }
  return report_results(report, o.output, o.quiet);
}

}  // namespace vesper::cli
