// The `vesper-job/1` reader (job_file.h), apart from `vesper submit` so that
// its fuzz target (tests/fuzz/job_target.cpp) and tests can call it alone.
#include "cli/job_file.h"

#include <nlohmann/json.hpp>

#include "common/json_parse.h"
#include "common/json_reader.h"
#include "protocol/fields.h"
#include "server/requests.h"

namespace vesper::cli {
namespace {

constexpr std::string_view kJobFormat = "vesper-job/1";

// "frames": a range string ("1-100x5") or a single frame number.
std::string frame_range_text(const JsonReader& node) {
  if (node.json().is_number_integer()) return std::to_string(node.json().get<long long>());
  if (!node.json().is_string())
    node.fail("expected a frame range string like \"1-100x5\", got " + describe_json(node.json()));
  return node.as_string();
}

}  // namespace

std::string default_job_name(const std::filesystem::path& scene) {
  // scenes/night-room/scene.json -> night-room
  if (scene.stem() == "scene" && scene.has_parent_path())
    return std::filesystem::absolute(scene).parent_path().filename().string();
  return scene.stem().string();
}

bool is_job_file_text(const std::string& text) {
  nlohmann::json doc;
  try {
    // The shared reader (its depth limit); a scene that does not parse is
    // reported by the scene loader with its line and column.
    doc = parse_json(text, "");
  } catch (const JsonError&) {
    return false;
  }
  if (!doc.is_object()) return false;
  const auto format = doc.find("format");
  // Not doc.value("format", ""): it throws nlohmann's type_error for a
  // "format" that is not a string.
  return format != doc.end() && format->is_string() && format->get<std::string>() == kJobFormat;
}

JobRequest read_job_file(const std::filesystem::path& file, JobRequest defaults) {
  return parse_job_file_text(read_text_file(file, "the job file"), file, std::move(defaults));
}

JobRequest parse_job_file_text(const std::string& text, const std::filesystem::path& file,
                               JobRequest r) {
  const nlohmann::json doc = parse_json(text, file.string());
  JsonReader root(doc, file.string(), "");
  root.expect_object();
  root.child("format").expect_string(kJobFormat);
  namespace f = protocol::field;
  root.allow_keys({"format", f::kScene, f::kName, f::kFrames, f::kSpp, f::kSamplesPerTask,
                   f::kPriority, f::kMaxAttempts, f::kNoiseTarget, f::kMinSpp, f::kMaxSpp,
                   f::kTimeLimit, f::kAovs, f::kLayerVariance, f::kSeed, f::kScale, f::kHalf,
                   f::kTaskTimeout});
  const std::filesystem::path scene = root.string("scene");
  r.scene = scene.is_relative() ? file.parent_path() / scene : scene;
  r.name = root.has("name") ? root.string("name") : default_job_name(r.scene);
  if (const auto frames = root.optional_child("frames")) r.frames = frame_range_text(*frames);
  r.spp = int(root.integer("spp", r.spp, 1, 1 << 20));
  r.samples_per_task = int(root.integer("samples_per_task", r.samples_per_task, 0, 1 << 20));
  r.priority = int(root.integer("priority", r.priority, -1000000, 1000000));
  r.max_attempts = int(root.integer("max_attempts", r.max_attempts, 1, 100));
  // Each key alone here; together with the flags and the scene in settle_job_request.
  const BudgetRequest keys = read_budget_request(root);
  BudgetRequest& b = r.sampling;
  if (keys.budget.noise_target) b.budget.noise_target = keys.budget.noise_target;
  if (keys.budget.min_spp) b.budget.min_spp = keys.budget.min_spp;
  if (keys.max_spp) b.max_spp = keys.max_spp;
  if (keys.budget.time_limit) b.budget.time_limit = keys.budget.time_limit;
  r.overrides = read_render_overrides(root);
  if (const auto t = root.optional_child(f::kTaskTimeout))
    r.task_timeout = t->as_number(Range::left_open(0, 30 * 86400));
  return r;
}

}  // namespace vesper::cli
