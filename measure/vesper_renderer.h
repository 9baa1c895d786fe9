#pragma once
// Vesper as a measured renderer: in this process, the scene loaded, its film
// resized to the benchmark's size, rendered at a fixed spp (adaptive sampling
// and time budgets switched off: the ladder decides), beauty only (no AOVs,
// no layers, no variant passes: they are not what is scored).
#include <cstddef>
#include <functional>
#include <string>

#include "measure/bench_renderer.h"

namespace vesper::measure {

struct VesperRendererOptions {
  // Called from worker threads after each tile of a render (thread-safe sink).
  std::function<void(size_t tiles_done, size_t tiles_total)> on_progress;
};

BenchRenderer vesper_renderer(const VesperRendererOptions& options = {});

// "vesper <VESPER_VERSION> build <id>": the id is the running executable's
// GNU build-id (a hash the linker computes over the linked code, so it changes
// exactly when the code does, and survives copies and `touch`), or, for a
// binary linked without one, its size and modification time.
std::string vesper_cache_key();

}  // namespace vesper::measure
