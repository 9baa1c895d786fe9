#include "server/requests.h"

#include <algorithm>
#include <climits>
#include <set>

#include "common/control_characters.h"
#include "common/json_parse.h"
#include "common/json_reader.h"
#include "common/sha256.h"
#include "common/utf8.h"
#include "jobs/frame_range.h"
#include "protocol/fields.h"
#include "renderer/scene/aov_list.h"
#include "server/api_error.h"

namespace vesper {
namespace {

namespace f = protocol::field;

constexpr const char* kBody = "request body";

// Seconds a task's render may take: more than a month is a typo.
const Range kTaskTimeoutRange = Range::left_open(0, 30 * 86400);

// Parses `body` and reads its root with `read`; a JsonError becomes ApiError
// 400 at its JSON path.
template <class Read>
auto read_body(const std::string& body, Read&& read) {
  try {
    const nlohmann::json j = parse_json(body, kBody);
    JsonReader root(j, kBody, "");
    return read(root);
  } catch (const JsonError& e) {
    // The reader names the whole body "/"; the API leaves `path` out for it.
    const std::string path = e.json_path() == "/" ? "" : e.json_path();
    throw ApiError(400, e.json_path().empty() ? e.what() : e.message(), path);
  }
}

// A required key, named at its own path when missing (the API's error paths
// name the field: "/frames").
JsonReader required(JsonReader& o, std::string_view key) {
  if (!o.has(key)) o.fail_key(key, "missing required key '" + std::string(key) + "'");
  return o.child(key);
}

std::string optional_string(JsonReader& o, std::string_view key) {
  const auto c = o.optional_child(key);
  return c ? c->as_string(/*allow_empty=*/true) : std::string();
}

// A SHA-256 spelling at `key` ("expected the SHA-256 of <what> ...").
std::string sha256_at(JsonReader& o, std::string_view key, const std::string& what) {
  const JsonReader v = required(o, key);
  if (!v.json().is_string() || !is_sha256_hex(v.json().get<std::string>()))
    v.fail("expected the SHA-256 of " + what + " (64 lower-case hex digits), got " +
           describe_json(v.json()));
  return v.json().get<std::string>();
}

// A name quoted in a message: at most 80 bytes, control characters escaped.
std::string shown(const std::string& name) {
  return escape_control_characters(utf8_safe(name, 80));
}

// A name people will read on terminals and in file names (a job's, a
// worker's): `max_bytes` at most, no control characters.
std::string read_name(JsonReader& o, std::string_view key, size_t max_bytes,
                      const std::string& fallback = {}) {
  const auto node = o.optional_child(key);
  if (!node) {
    if (fallback.empty()) o.fail_key(key, "missing required key '" + std::string(key) + "'");
    return fallback;
  }
  const std::string name = node->as_string(/*allow_empty=*/!fallback.empty());
  if (name.size() > max_bytes)
    o.fail_key(key, "name longer than " + std::to_string(max_bytes) + " characters");
  if (const std::string why = control_character_problem(name); !why.empty())
    o.fail_key(key, "name '" + shown(name) + "' " + why);
  return name;
}

Asset read_asset(JsonReader a, std::set<std::string>& names, std::set<std::string>& dirs) {
  a.allow_keys({f::kName, f::kBlob});
  Asset asset;
  asset.name = required(a, f::kName).as_string(/*allow_empty=*/true);
  if (const std::string why = asset_name_problem(asset.name); !why.empty())
    a.fail_key(f::kName, "asset name '" + shown(asset.name) + "' " + why);
  if (asset.name == "scene.json")
    a.fail_key(f::kName, "asset name 'scene.json' is reserved for the scene itself");
  if (!names.insert(asset.name).second)
    a.fail_key(f::kName, "duplicate asset name '" + shown(asset.name) + "'");
  for (size_t slash = asset.name.find('/'); slash != std::string::npos;
       slash = asset.name.find('/', slash + 1))
    dirs.insert(asset.name.substr(0, slash));
  asset.blob = sha256_at(a, f::kBlob, "an uploaded blob");
  return asset;
}

std::vector<Asset> read_assets(const JsonReader& assets) {
  if (!assets.json().is_array())
    assets.fail("expected an array of {\"name\", \"blob\"} objects, got " +
                describe_json(assets.json()));
  if (assets.size() > size_t(kMaxAssetsPerJob))
    assets.fail("more than " + std::to_string(kMaxAssetsPerJob) + " assets");
  std::vector<Asset> out;
  std::set<std::string> names, dirs;  // dirs: every directory some name needs
  for (size_t i = 0; i < assets.size(); ++i)
    out.push_back(read_asset(assets.element(i), names, dirs));
  // A name cannot be a file and a directory at once ("a" and "a/b").
  for (size_t i = 0; i < out.size(); ++i)
    if (dirs.count(out[i].name))
      assets.element(i).fail_key(f::kName, "asset name '" + shown(out[i].name) +
                                               "' is also the directory of another asset");
  return out;
}

// "1-100x5" or [1, 5, 9]: sorted, without repeats.
std::vector<int> read_frames(const JsonReader& frames) {
  if (frames.json().is_string()) {
    try {
      return parse_frame_range(frames.json().get<std::string>());
    } catch (const FrameRangeError& e) {
      frames.fail(std::string("bad frame range: ") + e.what());
    }
  }
  if (!frames.json().is_array())
    frames.fail(
        "expected a frame range string (\"1-100\", \"1-100x5\", \"1,5,9\") or an array of "
        "integers, got " +
        describe_json(frames.json()));
  if (frames.size() == 0) frames.fail("expected at least one frame");
  std::vector<int> out;
  for (size_t i = 0; i < frames.size(); ++i)
    out.push_back(int(frames.element(i).as_integer(INT32_MIN, INT32_MAX)));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

JobSpec read_job(JsonReader& o) {
  o.allow_keys({f::kName, f::kScene, f::kFrames, f::kSpp, f::kSamplesPerTask, f::kPriority,
                f::kMaxAttempts, f::kAssets, f::kNoiseTarget, f::kMinSpp, f::kMaxSpp, f::kTimeLimit,
                f::kAovs, f::kLayerVariance, f::kSeed, f::kScale, f::kHalf, f::kTaskTimeout});
  JobSpec spec;
  spec.name = read_name(o, f::kName, 256, "job");
  spec.scene = sha256_at(o, f::kScene, "an uploaded scene blob");
  spec.frames = read_frames(required(o, f::kFrames));
  spec.spp = int(o.integer(f::kSpp, spec.spp, 1, kMaxFrameSpp));
  spec.samples_per_task = int(o.integer(f::kSamplesPerTask, 0, 0, 1 << 20));
  spec.priority = int(o.integer(f::kPriority, spec.priority, -1000000, 1000000));
  spec.max_attempts = int(o.integer(f::kMaxAttempts, spec.max_attempts, 1, 100));
  if (const auto assets = o.optional_child(f::kAssets)) spec.assets = read_assets(*assets);
  const BudgetRequest budget = read_budget_request(o);
  if (const auto why = budget_problem(budget, spec.spp)) o.fail_key(why->field, why->message);
  spec.spp = budget.frame_spp(spec.spp);
  spec.budget = budget.budget;
  spec.overrides = read_render_overrides(o);
  if (const auto v = o.optional_child(f::kTaskTimeout))
    spec.task_timeout = v->as_number(kTaskTimeoutRange);
  const int64_t n = task_count(spec);
  if (n > kMaxTasksPerJob)
    o.fail_key(spec.samples_per_task > 0 ? f::kSamplesPerTask : f::kFrames,
               "the job splits into " + std::to_string(n) + " tasks, more than " +
                   std::to_string(kMaxTasksPerJob) +
                   " (fewer frames or a larger samples_per_task)");
  return spec;
}

}  // namespace

BudgetRequest read_budget_request(JsonReader& o) {
  BudgetRequest r;
  if (const auto v = o.optional_child(f::kNoiseTarget))
    r.budget.noise_target = v->as_number(Range::positive());
  if (const auto v = o.optional_child(f::kMinSpp))
    r.budget.min_spp = int(v->as_integer(1, kMaxFrameSpp));
  if (const auto v = o.optional_child(f::kMaxSpp)) r.max_spp = int(v->as_integer(1, kMaxFrameSpp));
  if (const auto v = o.optional_child(f::kTimeLimit))
    r.budget.time_limit = v->as_number(Range::positive());
  return r;
}

RenderOverrides read_render_overrides(JsonReader& o) {
  RenderOverrides r;
  if (const auto v = o.optional_child(f::kAovs)) {
    // Checked as the renderer reads render.aovs, so a task cannot fail on them.
    for (const Aov a : read_aov_list(*v)) r.aovs.emplace_back(kAovNames[size_t(a)]);
    if (r.aovs.empty()) v->fail("expected at least one AOV (leave the key out for the scene's)");
  }
  r.layer_variance = o.boolean(f::kLayerVariance, false);
  if (const auto v = o.optional_child(f::kSeed)) r.seed = uint64_t(v->as_integer(0, INT64_MAX));
  if (const auto v = o.optional_child(f::kScale))
    r.scale = v->as_number(Range::left_open(0, kMaxFilmScale));
  r.half = o.boolean(f::kHalf, false);
  return r;
}

int64_t task_count(const JobSpec& spec) {
  const int64_t split = spec.samples_per_task > 0 ? spec.samples_per_task : spec.spp;
  return int64_t(spec.frames.size()) * ((spec.spp + split - 1) / split);
}

JobSpec read_job_request(const std::string& body) { return read_body(body, read_job); }

protocol::RegisterRequest read_register_request(const std::string& body) {
  return read_body(body, [](JsonReader& o) {
    o.allow_keys({f::kName, f::kWorkerId});
    protocol::RegisterRequest r{read_name(o, f::kName, 128), optional_string(o, f::kWorkerId)};
    if (r.worker_id.size() > 64) o.fail_key(f::kWorkerId, "expected a worker id this server gave");
    return r;
  });
}

protocol::GoodbyeRequest read_goodbye_request(const std::string& body) {
  return read_body(body, [](JsonReader& o) {
    o.allow_keys({f::kWorkerId});
    return protocol::GoodbyeRequest{required(o, f::kWorkerId).as_string()};
  });
}

protocol::LeaseRequest read_lease_request(const std::string& body) {
  return read_body(body, [](JsonReader& o) {
    o.allow_keys({f::kWorkerId, f::kRenderer});
    protocol::LeaseRequest r{required(o, f::kWorkerId).as_string(),
                             optional_string(o, f::kRenderer)};
    // The renderer's identity (sha256 of its executable); empty: not given.
    if (!r.renderer.empty() && !is_sha256_hex(r.renderer))
      o.fail_key(f::kRenderer, "expected the renderer's sha256 (64 lower-case hex digits)");
    return r;
  });
}

protocol::HeartbeatRequest read_heartbeat_request(const std::string& body) {
  return read_body(body, [](JsonReader& o) {
    o.allow_keys({f::kLeaseId, f::kProgress});
    return protocol::HeartbeatRequest{required(o, f::kLeaseId).as_string(),
                                      o.number(f::kProgress, 0, Range::closed(0, 1))};
  });
}

protocol::CompleteRequest read_complete_request(const std::string& body) {
  return read_body(body, [](JsonReader& o) {
    o.allow_keys({f::kLeaseId, f::kResult, f::kLog});
    return protocol::CompleteRequest{required(o, f::kLeaseId).as_string(),
                                     sha256_at(o, f::kResult, "the uploaded result blob"),
                                     optional_string(o, f::kLog)};
  });
}

protocol::FailRequest read_fail_request(const std::string& body) {
  return read_body(body, [](JsonReader& o) {
    o.allow_keys({f::kLeaseId, f::kLog});
    return protocol::FailRequest{required(o, f::kLeaseId).as_string(), optional_string(o, f::kLog)};
  });
}

}  // namespace vesper
