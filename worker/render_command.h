#pragma once
// The one place the worker's child render command line is built, from the
// leased task and the worker's configuration.
#include <filesystem>
#include <string>
#include <vector>

#include "protocol/worker_messages.h"
#include "worker/worker.h"

namespace vesper::worker_detail {

// `vesper render <scene_file> -o <output> --spp S --sample-begin B
// --sample-end E --frame F [--partial] [--noise-target X --max-spp S]
// [--min-spp M] [--time-limit T] [--aov A,B] [--layer-variance] [--seed S]
// [--scale X] [--threads N]`: the budget flags are the task's share of its
// frame's budget, as the lease carries it (exact: the shortest text of each
// double); --max-spp pins the frame's spp to the job's over the scene's
// render.max_spp. --aov, --layer-variance, --seed and --scale are the job's
// render overrides, when it has them. Without --seed the renderer takes the
// scene's own render.seed; either way --frame decorrelates the frames from
// it, exactly as a local `vesper render --frame F` does. No -q:
// the render's plain progress lines on stderr feed the heartbeat's progress
// and give failure logs context.
// A sample range that is not the whole frame renders a partial (exact
// sample sums, docs/partial-format.md) for the server's `vesper merge`.
bool renders_partial(const protocol::LeaseResponse& lease);

std::vector<std::string> render_command(const protocol::LeaseResponse& lease,
                                        const WorkerConfig& config,
                                        const std::filesystem::path& scene_file,
                                        const std::filesystem::path& output);

// ".vpartial" for a sample range that is not the whole frame, else ".exr".
std::string render_output_extension(const protocol::LeaseResponse& lease);

// ", noise target 0.02 (min spp 16), time limit 7.5 s" for logs; "" without a budget.
std::string describe_budget(const protocol::LeaseResponse& lease);

// argv joined with spaces, for logs.
std::string command_line(const std::vector<std::string>& argv);

}  // namespace vesper::worker_detail
