#pragma once
// Blender Cycles as a measured peer of `vesper bench --compare cycles`: each
// render runs `blender -b --factory-startup --python vesper_to_cycles.py`
// (bench/cycles/) as a child process, which translates the vesper-scene/1
// file, renders it and writes an EXR and a stats JSON; this reads them back.
// Blender is a benchmark-only peer: `scripts/setup --peers` installs it.
#include <cstddef>
#include <functional>
#include <string>
#include <utility>

#include "measure/bench_renderer.h"

namespace vesper::measure {

struct CyclesRendererOptions {
  std::string blender = "blender";  // a path, or a name looked up on PATH
  std::string script;               // path to bench/cycles/vesper_to_cycles.py
  std::string work_dir;             // where the per-render EXR and stats JSON go (created)
  // Samples done of the render's total, read from Blender's "Sample N/M"
  // status lines while it renders (a reference can take minutes).
  std::function<void(size_t done, size_t total)> on_progress;
};

// The last "Sample N/M" of Blender's status output, as {N, M}; {0, 0} when
// there is none yet.
std::pair<size_t, size_t> last_sample_status(const std::string& output);

// name "cycles"; cache_key = `blender --version`'s first line + a sha256 of
// the script and the modules beside it (queried once, here). Throws std::runtime_error when blender
// is missing (saying how to install it) or the script cannot be read. render() throws
// std::runtime_error naming the scene, "cycles", the exit status and the stderr tail when blender
// fails or refuses the scene.
BenchRenderer cycles_renderer(const CyclesRendererOptions& options);

// The executable `blender` names: itself if it holds a '/', else the first
// match on $PATH; empty if there is none (or it is not executable).
std::string find_executable(const std::string& blender);

}  // namespace vesper::measure
