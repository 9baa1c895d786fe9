#pragma once
// The job file, `vesper-job/1` (docs/farm.md, "Job files"): a job's settings
// versioned beside its scene. `vesper submit` reads it over the farm's
// defaults; flags override it.
#include <filesystem>
#include <optional>
#include <string>

#include "jobs/render_budget.h"
#include "jobs/render_overrides.h"

namespace vesper::cli {

struct JobRequest {
  std::filesystem::path scene;
  std::string name;
  std::string frames;
  int spp = 0;  // 0 = the scene's render.spp
  int samples_per_task = 0;
  int priority = 50;
  int max_attempts = 3;
  // Noise target, min/max spp, time limit per frame; each unset = the
  // scene's render.* (docs/farm.md, "Noise targets and time limits").
  BudgetRequest sampling;
  // AOVs, per-layer variance, seed, film scale of every render (docs/farm.md,
  // "Render overrides"); unset = as the scene says.
  RenderOverrides overrides;
  std::optional<double> task_timeout;  // seconds per task render; unset = the server's default
};

// The job's default name: the scene's folder for `<folder>/scene.json`, else its stem.
std::string default_job_name(const std::filesystem::path& scene);

// Whether `text` is a job file (an object whose "format" is "vesper-job/1")
// rather than a scene. Never throws: anything else (invalid JSON, another
// format, a "format" that is not a string) is not a job file.
bool is_job_file_text(const std::string& text);

// Reads a job file over `defaults`. Throws JsonError "<file>: <json path>:
// <what was expected>" (an unreadable file too).
JobRequest read_job_file(const std::filesystem::path& file, JobRequest defaults);
// The same from the file's text: `file` names it in messages and the scene
// path resolves against its folder.
JobRequest parse_job_file_text(const std::string& text, const std::filesystem::path& file,
                               JobRequest defaults);

}  // namespace vesper::cli
