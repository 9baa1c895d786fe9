#include "jobs/job.h"

#include <algorithm>
#include <filesystem>

#include "common/control_characters.h"
#include "common/scene_reference.h"

namespace vesper {

const char* to_string(TaskState s) {
  switch (s) {
    case TaskState::Queued:
      return "queued";
    case TaskState::Leased:
      return "leased";
    case TaskState::Done:
      return "done";
    case TaskState::Failed:
      return "failed";
    case TaskState::Canceled:
      return "canceled";
    case TaskState::Paused:
      return "paused";
  }
  return "?";
}
const char* to_string(JobState s) {
  switch (s) {
    case JobState::Active:
      return "active";
    case JobState::Paused:
      return "paused";
    case JobState::Done:
      return "done";
    case JobState::Failed:
      return "failed";
    case JobState::Canceled:
      return "canceled";
  }
  return "?";
}

std::optional<double> estimate_eta(const JobSummary& job, double now) {
  const int rendered = job.done - job.reused;
  if (job.state != JobState::Active || !job.started_at || rendered <= 0) return std::nullopt;
  const int remaining = job.queued + job.leased + job.paused;
  return std::max(0.0, now - *job.started_at) * remaining / rendered;
}

std::string normal_asset_name(std::string_view name) {
  return std::filesystem::path(name).lexically_normal().generic_string();
}

std::string asset_name_problem(std::string_view name) {
  if (name.empty()) return "expected a non-empty relative path";
  if (name.size() > kMaxAssetNameLength)
    return "longer than " + std::to_string(kMaxAssetNameLength) + " characters";
  if (std::string why = control_character_problem(name); !why.empty()) return why;
  if (name.find('\\') != std::string_view::npos)
    return "contains a backslash (use '/' to separate directories)";
  // Absolute paths and '..': the rule every file a scene references follows.
  if (std::string why = outside_reference_problem(name); !why.empty()) return why;
  // Beyond it, names are canonical (no empty or '.' segment): one file, one name.
  for (size_t begin = 0;;) {
    const size_t end = std::min(name.find('/', begin), name.size());
    const std::string_view seg = name.substr(begin, end - begin);
    if (seg.empty()) return "has an empty path segment ('//' or a trailing '/')";
    if (seg == ".") return "has a '.' segment (expected a canonical relative path)";
    if (end == name.size()) break;
    begin = end + 1;
  }
  return {};
}

}  // namespace vesper
