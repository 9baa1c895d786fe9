#include "worker/render_command.h"

#include "jobs/render_budget.h"
#include "jobs/render_overrides.h"

namespace vesper::worker_detail {

bool renders_partial(const protocol::LeaseResponse& lease) {
  return lease.task.sample_begin != 0 || lease.task.sample_end != lease.spp;
}

std::vector<std::string> render_command(const protocol::LeaseResponse& lease,
                                        const WorkerConfig& config,
                                        const std::filesystem::path& scene_file,
                                        const std::filesystem::path& output) {
  std::vector<std::string> argv = {config.vesper_binary.string(),
                                   "render",
                                   scene_file.string(),
                                   "-o",
                                   output.string(),
                                   "--spp",
                                   std::to_string(lease.spp),
                                   "--sample-begin",
                                   std::to_string(lease.task.sample_begin),
                                   "--sample-end",
                                   std::to_string(lease.task.sample_end),
                                   "--frame",
                                   std::to_string(lease.task.frame)};
  // The scene came from a submitter: the files it reads must be in the task
  // directory, never elsewhere on this machine.
  argv.push_back("--scene-dir-only");
  if (renders_partial(lease)) argv.push_back("--partial");
  // This task's share of its frame's budget (jobs/render_budget.h).
  auto add = [&argv](const char* flag, const std::string& value) {
    argv.push_back(flag);
    argv.push_back(value);
  };
  if (lease.noise_target) {
    add("--noise-target", exact_text(*lease.noise_target));
    // The frame's spp is the job's, whatever render.max_spp the scene says.
    add("--max-spp", std::to_string(lease.spp));
  }
  if (lease.min_spp) add("--min-spp", std::to_string(*lease.min_spp));
  if (lease.time_limit) add("--time-limit", exact_text(*lease.time_limit));
  // The job's render overrides (jobs/render_overrides.h).
  if (!lease.aovs.empty()) add("--aov", join_aovs(lease.aovs));
  if (lease.layer_variance) argv.push_back("--layer-variance");
  if (lease.seed) add("--seed", std::to_string(*lease.seed));
  if (lease.scale) add("--scale", exact_text(*lease.scale));
  if (lease.half) argv.push_back("--half");
  if (config.render_threads > 0) {
    argv.push_back("--threads");
    argv.push_back(std::to_string(config.render_threads));
  }
  return argv;
}

std::string render_output_extension(const protocol::LeaseResponse& lease) {
  return renders_partial(lease) ? ".vpartial" : ".exr";
}

std::string describe_budget(const protocol::LeaseResponse& l) {
  std::string s;
  if (l.noise_target) s += ", noise target " + exact_text(*l.noise_target);
  if (l.min_spp) s += " (min spp " + std::to_string(*l.min_spp) + ")";
  if (l.time_limit) s += ", time limit " + exact_text(*l.time_limit) + " s";
  return s;
}

std::string command_line(const std::vector<std::string>& argv) {
  std::string line;
  for (const auto& a : argv) line += (line.empty() ? "" : " ") + a;
  return line;
}

}  // namespace vesper::worker_detail
