// vesper submit: a scene or a job file to the farm.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/job_watch.h"
#include "cli/scene_package.h"
#include "cli/submit.h"
#include "common/json_parse.h"
#include "common/json_reader.h"
#include "common/sha256.h"
#include "jobs/frame_range.h"
#include "protocol/fields.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"
#include "renderer/scene/scene_loader.h"
#include "server/requests.h"

namespace vesper::cli {
namespace {

// A temp file for the packed scene, removed when the upload is done.
struct TempFile {
  std::filesystem::path path;
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

// Uploads the packed scene (through a temp file) and returns its hash.
std::string upload_scene(FarmClient& client, const std::string& json) {
  TempFile tmp{std::filesystem::temp_directory_path() /
               ("vesper-submit-" + std::to_string(::getpid()) + ".json")};
  {
    std::ofstream out(tmp.path, std::ios::binary);
    out << json;
    if (!out.flush()) throw FarmClientError(tmp.path.string() + ": cannot write");
  }
  return client.put_blob(tmp.path);
}

}  // namespace

JobRequest job_request_defaults(const FarmSettings& s, const std::filesystem::path& scene) {
  JobRequest r;
  r.scene = scene;
  r.name = default_job_name(scene);
  r.frames = s.job.frames;
  r.spp = s.job.spp;
  r.samples_per_task = s.job.samples_per_task;
  r.priority = s.job.priority;
  r.max_attempts = s.job.max_attempts;
  // 0 in farm.toml: the scene's.
  BudgetRequest& b = r.sampling;
  if (s.job.noise_target > 0) b.budget.noise_target = s.job.noise_target;
  if (s.job.min_spp > 0) b.budget.min_spp = s.job.min_spp;
  if (s.job.max_spp > 0) b.max_spp = s.job.max_spp;
  if (s.job.time_limit > 0) b.budget.time_limit = s.job.time_limit;
  if (s.job.task_timeout > 0) r.task_timeout = s.job.task_timeout;
  return r;
}

void apply_sampling_flags(BudgetRequest& b, const SamplingFlags& flags) {
  if (flags.noise_target) b.budget.noise_target = flags.noise_target;
  if (flags.min_spp) b.budget.min_spp = flags.min_spp;
  if (flags.max_spp) b.max_spp = flags.max_spp;
  if (flags.time_limit) b.budget.time_limit = flags.time_limit;
}

JobRequest settle_job_request(JobRequest r, int first_frame) {
  const RenderDesc render = load_scene(r.scene, {.frame = double(first_frame)}).render;
  if (r.spp <= 0) r.spp = render.spp;
  BudgetRequest& b = r.sampling;
  if (!b.budget.noise_target) b.budget.noise_target = render.noise_target;
  if (!b.budget.time_limit) b.budget.time_limit = render.time_limit;
  // The scene's min/max spp go with a noise target only (as for `vesper
  // render`); the request's own without one are errors below.
  if (b.budget.noise_target) {
    if (!b.budget.min_spp) b.budget.min_spp = render.min_spp;
    if (!b.max_spp) b.max_spp = render.max_spp;
  }
  std::optional<BudgetProblem> why = budget_problem(b, r.spp);
  if (!why && b.frame_spp(r.spp) > kMaxFrameSpp)
    why = BudgetProblem{"max_spp", "expected at most " + std::to_string(kMaxFrameSpp) + ", got " +
                                       std::to_string(*b.max_spp)};
  if (why) {
    std::string flag = std::string("--") + why->field;
    std::replace(flag.begin(), flag.end(), '_', '-');
    throw JobRequestError(flag + " (" + why->field + " in a job file, render." + why->field +
                          " in the scene): " + why->message);
  }
  return r;
}

Submitted submit_job(FarmClient& client, const JobRequest& request, bool dry_run) {
  // The scene is checked here, where its author can fix it, before anything is
  // uploaded (and fills in what the request leaves to it); the frame range
  // too (the server checks again).
  const std::vector<int> frames = parse_frame_range(request.frames);
  const JobRequest r = settle_job_request(request, frames.front());
  const PackedScene packed = pack_scene(r.scene, frames);

  protocol::SubmitRequest body;
  // A dry run uploads nothing: the blobs are named by their local hashes
  // (the server checks the request without them).
  for (const PackedAsset& a : packed.assets) {
    const std::string sha = dry_run ? a.sha256 : client.put_blob(a.local);
    if (sha != a.sha256)
      throw FarmClientError(a.local.string() + ": changed while it was being submitted");
    body.assets.push_back({a.name, sha});
  }
  body.scene = dry_run ? sha256_hex(packed.json) : upload_scene(client, packed.json);
  body.name = r.name;
  body.frames = r.frames;
  body.spp = r.spp;
  body.samples_per_task = r.samples_per_task;
  body.priority = r.priority;
  body.max_attempts = r.max_attempts;
  body.noise_target = r.sampling.budget.noise_target;
  body.min_spp = r.sampling.budget.min_spp;
  body.max_spp = r.sampling.max_spp;
  body.time_limit = r.sampling.budget.time_limit;
  body.aovs = r.overrides.aovs;
  body.layer_variance = r.overrides.layer_variance;
  body.seed = r.overrides.seed;
  body.scale = r.overrides.scale;
  body.half = r.overrides.half;
  body.task_timeout = r.task_timeout;

  std::string path(protocol::paths::kJobs);
  if (dry_run) path += "?" + std::string(protocol::kDryRunParam) + "=1";
  const nlohmann::json answer = client.post_json(path, body);
  Submitted s;
  if (dry_run) {
    s.task_count = int(answer.get<protocol::DryRunResponse>().task_count);
  } else {
    const auto created = answer.get<protocol::SubmitResponse>();
    s.id = created.id;
    s.task_count = int(created.task_count);
  }
  return s;
}

int run_submit(const SubmitCommandOptions& o) {
  try {
    const FarmSettings settings = load_farm_settings(o.farm.config);
    JobRequest r = job_request_defaults(settings, o.input);
    std::string text;
    if (std::ifstream in(o.input, std::ios::binary); in)
      text.assign(std::istreambuf_iterator<char>(in), {});
    if (is_job_file_text(text)) r = parse_job_file_text(text, o.input, r);
    if (o.frames) r.frames = *o.frames;
    if (o.name) r.name = *o.name;
    if (o.spp) r.spp = *o.spp;
    if (o.samples_per_task) r.samples_per_task = *o.samples_per_task;
    if (o.priority) r.priority = *o.priority;
    if (o.max_attempts) r.max_attempts = *o.max_attempts;
    apply_sampling_flags(r.sampling, o.sampling);
    if (o.half) r.overrides.half = true;

    const std::string url = resolve_server_url(settings, o.farm.server);
    FarmClient client(url, resolve_token(settings, url, o.farm.token, TokenRole::Submitter));
    const Submitted s = submit_job(client, r, o.dry_run);
    if (o.dry_run) {
      spdlog::info("dry run: '{}' frames {} would make {} tasks; nothing was created", r.name,
                   r.frames, s.task_count);
      return 0;
    }
    spdlog::info("submitted job {} '{}': frames {}, {} tasks", s.id, r.name, r.frames,
                 s.task_count);
    std::printf("%lld\n", s.id);
    std::fflush(stdout);
    if (!o.wait) return 0;
    protocol::JobDetail j = wait_for_job(client, s.id);
    j.frames = wait_for_merges(client, s.id).frames;  // a split frame's noise is its merge's
    spdlog::info("{}", describe_job(j));
    return j.summary.state == "done" ? 0 : 3;  // failed, canceled, or stuck (every worker blocked)
  } catch (const SceneError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const JobRequestError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const FarmConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const FarmClientError& e) {
    spdlog::error("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
}

}  // namespace vesper::cli
