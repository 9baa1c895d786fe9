#include "protocol/paths.h"

#include <stdexcept>

namespace vesper::protocol {

std::string api(std::string_view relative) {
  std::string out(kApiPrefix);
  out += relative;
  return out;
}

std::string expand(std::string_view path_template, std::initializer_list<std::string_view> values) {
  std::string out;
  auto value = values.begin();
  for (size_t i = 0; i < path_template.size(); ++i) {
    if (path_template[i] != '{') {
      out += path_template[i];
      continue;
    }
    const size_t close = path_template.find('}', i);
    if (close == std::string_view::npos || value == values.end())
      throw std::invalid_argument("expand: more parameters than values in '" +
                                  std::string(path_template) + "'");
    out += *value++;
    i = close;
  }
  if (value != values.end())
    throw std::invalid_argument("expand: more values than parameters in '" +
                                std::string(path_template) + "'");
  return out;
}

std::string_view action_template(JobAction action) {
  constexpr std::string_view kTemplates[] = {paths::kJobCancel, paths::kJobPause, paths::kJobResume,
                                             paths::kJobRetryFailed};
  return kTemplates[size_t(action)];
}

std::string_view action_name(JobAction action) {
  const std::string_view t = action_template(action);
  return t.substr(t.rfind('/') + 1);
}

std::string job_path(int64_t job) { return expand(paths::kJob, {std::to_string(job)}); }

std::string job_action_path(int64_t job, JobAction action) {
  return expand(action_template(action), {std::to_string(job)});
}

std::string task_log_path(int64_t job, int64_t task) {
  return expand(paths::kTaskLog, {std::to_string(job), std::to_string(task)});
}

std::string frames_path(int64_t job) { return expand(paths::kFrames, {std::to_string(job)}); }

std::string frame_path(int64_t job, int frame) {
  return expand(paths::kFrame, {std::to_string(job), std::to_string(frame)});
}

std::string blob_path(std::string_view sha256) { return expand(paths::kBlob, {sha256}); }

}  // namespace vesper::protocol
