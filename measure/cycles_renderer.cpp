#include "measure/cycles_renderer.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "common/sha256.h"
#include "process/child_process.h"
#include "renderer/output/exr_io.h"

namespace vesper::measure {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kStderrTailBytes = 4096;  // what an error message quotes

// Runs argv to completion (no time limit: a render takes what it takes),
// reporting Blender's sample count when asked to.
void run_to_exit(ChildProcess& child,
                 const std::function<void(size_t, size_t)>& on_progress = nullptr) {
  while (!child.wait_for(0.25))
    if (on_progress)
      if (const auto [done, total] = last_sample_status(child.stderr_tail()); total > 0)
        on_progress(done, total);
}

std::string first_line(const std::string& text) {
  const auto end = text.find('\n');
  return text.substr(0, end == std::string::npos ? text.size() : end);
}

std::string blender_version(const std::string& blender) {
  ChildProcess child({blender, "--version"}, kStderrTailBytes, ChildStdout::into_tail);
  run_to_exit(child);
  const std::string line = first_line(child.stderr_tail());
  if (child.exit_code() != 0 || line.rfind("Blender ", 0) != 0)
    throw std::runtime_error("cycles: '" + blender +
                             " --version' did not name a Blender version (" +
                             child.describe_status() + "): " + line);
  return line;
}

std::string missing_blender_message(const std::string& blender) {
  return "cycles: Blender not found ('" + blender +
         "' is not an executable file or on PATH); the Cycles comparison needs it: install it "
         "with `scripts/setup --peers` (Debian package blender)";
}

// The beauty and the renderer's own time, from the files the script wrote.
RenderedImage read_outputs(const fs::path& exr, const fs::path& stats, const BenchScene& scene) {
  RenderedImage result;
  result.image = read_exr(exr);
  std::ifstream in(stats);
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.contains("render_seconds") || !j["render_seconds"].is_number())
    throw std::runtime_error("cycles: scene '" + scene.name + "': " + stats.string() +
                             ": expected a JSON object with a number render_seconds");
  result.render_seconds = j["render_seconds"].get<double>();
  return result;
}

struct CyclesRun {
  std::string blender, script;
  fs::path work_dir;
  std::function<void(size_t, size_t)> on_progress;

  RenderedImage operator()(const BenchScene& scene, int spp, uint64_t seed, int threads) const {
    static std::atomic<int> counter{0};
    const std::string stem =
        scene.name + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const fs::path exr = work_dir / (stem + ".exr"), stats = work_dir / (stem + ".json");
    std::vector<std::string> argv = {blender,
                                     "-b",
                                     "--factory-startup",
                                     "--python-exit-code",
                                     "2",
                                     "--python",
                                     script,
                                     "--",
                                     "--scene",
                                     scene.scene_path,
                                     "--spp",
                                     std::to_string(spp),
                                     "--seed",
                                     std::to_string(seed),
                                     "--threads",
                                     std::to_string(threads),
                                     "--out",
                                     exr.string(),
                                     "--stats",
                                     stats.string()};
    if (scene.width > 0 && scene.height > 0)
      argv.insert(argv.end(), {"--width", std::to_string(scene.width), "--height",
                               std::to_string(scene.height)});
    const auto start = Clock::now();
    // stdout too: it carries the "Sample N/M" status lines the progress reads.
    ChildProcess child(argv, kStderrTailBytes, ChildStdout::into_tail);
    run_to_exit(child, on_progress);
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    if (child.exit_code() != 0 || !fs::exists(exr) || !fs::exists(stats))
      throw std::runtime_error("cycles: scene '" + scene.name + "' (" + scene.scene_path +
                               "): blender failed (" + child.describe_status() +
                               "); stderr tail:\n" + child.stderr_tail());
    RenderedImage result;
    try {
      result = read_outputs(exr, stats, scene);
    } catch (const ImageIoError& e) {
      throw std::runtime_error("cycles: scene '" + scene.name + "': " + e.what());
    }
    result.wall_seconds = wall;
    std::error_code ignored;
    fs::remove(exr, ignored);
    fs::remove(stats, ignored);
    return result;
  }
};

// sha256 over the script and every other .py beside it (its modules), by
// name, so that editing any of them invalidates cached Cycles references.
std::optional<std::string> translation_hash(const fs::path& script) {
  std::error_code ec;
  if (!fs::is_regular_file(script, ec)) return std::nullopt;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(script.parent_path(), ec))
    if (entry.path().extension() == ".py") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  Sha256 all;
  for (const fs::path& file : files) {
    const auto hash = sha256_file(file);
    if (!hash) return std::nullopt;
    all.update(file.filename().string() + " " + *hash + "\n");
  }
  return all.hex();
}

}  // namespace

std::pair<size_t, size_t> last_sample_status(const std::string& output) {
  constexpr std::string_view kWord = "Sample ";
  for (size_t at = output.rfind(kWord); at != std::string::npos;
       at = at == 0 ? std::string::npos : output.rfind(kWord, at - 1)) {
    size_t done = 0, total = 0;
    char slash = 0;
    std::istringstream in(output.substr(at + kWord.size(), 24));
    if (in >> done >> slash >> total && slash == '/' && total > 0) return {done, total};
  }
  return {0, 0};
}

std::string find_executable(const std::string& blender) {
  const auto executable = [](const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
  };
  if (blender.find('/') != std::string::npos) return executable(blender) ? blender : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / blender;
    if (executable(candidate)) return candidate.string();
  }
  return "";
}

BenchRenderer cycles_renderer(const CyclesRendererOptions& options) {
  const std::string blender = find_executable(options.blender);
  if (blender.empty()) throw std::runtime_error(missing_blender_message(options.blender));
  const auto script_hash = translation_hash(fs::absolute(options.script));
  if (!script_hash)
    throw std::runtime_error("cycles: cannot read the translation script '" + options.script +
                             "' (bench/cycles/vesper_to_cycles.py)");
  fs::create_directories(options.work_dir);
  BenchRenderer renderer;
  renderer.name = "cycles";
  renderer.cache_key = blender_version(blender) + " translation sha256 " + *script_hash;
  renderer.render = CyclesRun{blender, fs::absolute(options.script).string(),
                              fs::absolute(options.work_dir), options.on_progress};
  return renderer;
}

}  // namespace vesper::measure
