#pragma once
// Renders and merges started by a farm worker must not outlive it: a worker
// killed with SIGKILL cannot stop its child (which leads its own process
// group), and an orphaned render would burn a machine's cores for nothing —
// its result can never be uploaded. The worker exports its pid as
// VESPER_PARENT_PID before it starts children; a child that finds it asks the
// kernel for SIGKILL when its parent dies (PR_SET_PDEATHSIG), and exits at
// once if the parent is already gone.
namespace vesper::cli {

// In `vesper worker` / `vesper up`, before any thread or child starts.
void export_parent_pid();
// In `vesper render` / `vesper merge`, first thing. Returns false if the
// parent named by VESPER_PARENT_PID is already gone (the caller exits).
bool die_with_parent();

}  // namespace vesper::cli
