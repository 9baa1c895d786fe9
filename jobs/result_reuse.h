#pragma once
// Result reuse: identical tasks are rendered once. Two tasks are identical
// when their jobs' inputs keys (scene blob, spp, render budget, render overrides, assets), frames,
// frame states (jobs/frame_states.h; then the key leaves out the scene blob and assets) and
// sample ranges are equal and the same renderer (an opaque id, e.g. the renderer executable's
// sha256) produced the done one.
#include <cstdint>
#include <string>

#include "jobs/job_store.h"

namespace vesper {

// What makes two jobs' tasks identical besides their frame and sample range:
// the scene blob, the spp, the render budget (noise target, min spp, time
// limit: a different target is a different result), the render overrides
// (AOVs, per-layer variance, seed, film scale) and the assets (name=blob, in
// name order). A job with frame states leaves the scene and assets out: its
// tasks' states hold them, frame by frame.
std::string inputs_key(const JobSpec& spec);

// Completes queued task `task_id` with the result of an identical task already
// done by `renderer` (recording the frame's output for a one-task frame) and
// returns true; false, touching nothing, when there is none or `renderer` is
// empty (= never reuse).
bool complete_from_identical_task(JobStore::Impl& store, int64_t task_id,
                                  const std::string& renderer, double now);

}  // namespace vesper
