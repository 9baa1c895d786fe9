#include "server/requests.h"

#include <algorithm>
#include <climits>
#include <nlohmann/json.hpp>
#include <set>

#include "jobs/frame_range.h"
#include "protocol/fields.h"
#include "server/api_error.h"
#include "server/json_body.h"
#include "common/sha256.h"

namespace vesper {

using nlohmann::json;
namespace f = protocol::field;

int64_t task_count(const JobSpec& spec) {
  const int64_t split = spec.samples_per_task > 0 ? spec.samples_per_task : spec.spp;
  return int64_t(spec.frames.size()) * ((spec.spp + split - 1) / split);
}

std::vector<Asset> read_assets(const json& assets) {
  const std::string where = std::string("/") + f::kAssets;
  if (!assets.is_array())
    throw ApiError(
        400,
        std::string("expected an array of {\"name\", \"blob\"} objects, got ") + assets.type_name(),
        where);
  if (assets.size() > size_t(kMaxAssetsPerJob))
    throw ApiError(400, "more than " + std::to_string(kMaxAssetsPerJob) + " assets", where);
  std::vector<Asset> out;
  std::set<std::string> names, dirs;  // dirs: every directory some name needs
  for (size_t i = 0; i < assets.size(); ++i) {
    const std::string at = where + "/" + std::to_string(i);
    const JsonObject a(assets[i], at, {f::kName, f::kBlob});
    Asset asset;
    const json& name = a.at(f::kName);
    if (!name.is_string())
      throw ApiError(400, std::string("expected a string, got ") + name.type_name(),
                     a.path(f::kName));
    asset.name = name.get<std::string>();
    std::string shown = asset.name.substr(0, 80);
    for (char& c : shown)
      if (static_cast<unsigned char>(c) < 0x20) c = '?';
    if (const std::string why = asset_name_problem(asset.name); !why.empty())
      throw ApiError(400, "asset name '" + shown + "' " + why, a.path(f::kName));
    if (asset.name == "scene.json")
      throw ApiError(400, "asset name 'scene.json' is reserved for the scene itself",
                     a.path(f::kName));
    if (!names.insert(asset.name).second)
      throw ApiError(400, "duplicate asset name '" + shown + "'", a.path(f::kName));
    for (size_t slash = asset.name.find('/'); slash != std::string::npos;
         slash = asset.name.find('/', slash + 1))
      dirs.insert(asset.name.substr(0, slash));
    const json& blob = a.at(f::kBlob);
    if (!blob.is_string() || !is_sha256_hex(blob.get<std::string>()))
      throw ApiError(400,
                     "expected the SHA-256 of an uploaded blob (64 lower-case hex digits), got " +
                         blob.dump().substr(0, 80),
                     a.path(f::kBlob));
    asset.blob = blob.get<std::string>();
    out.push_back(std::move(asset));
  }
  // A name cannot be a file and a directory at once ("a" and "a/b").
  for (size_t i = 0; i < out.size(); ++i)
    if (dirs.count(out[i].name))
      throw ApiError(
          400,
          "asset name '" + out[i].name.substr(0, 80) + "' is also the directory of another asset",
          where + "/" + std::to_string(i) + "/" + f::kName);
  return out;
}

JobSpec read_job_request(const json& body) {
  const JsonObject o(body, "",
                     {f::kName, f::kScene, f::kFrames, f::kSpp, f::kSamplesPerTask, f::kPriority,
                      f::kMaxAttempts, f::kAssets});
  JobSpec spec;
  spec.name = o.opt_string(f::kName).value_or("job");
  if (spec.name.size() > 256)
    throw ApiError(400, "name longer than 256 characters", o.path(f::kName));
  spec.scene = o.string(f::kScene);
  if (!is_sha256_hex(spec.scene))
    throw ApiError(400,
                   "expected the SHA-256 of an uploaded scene blob (64 lower-case hex digits), "
                   "got '" +
                       spec.scene.substr(0, 80) + "'",
                   o.path(f::kScene));
  const json& frames = o.at(f::kFrames);
  if (frames.is_string()) {
    try {
      spec.frames = parse_frame_range(frames.get<std::string>());
    } catch (const FrameRangeError& e) {
      throw ApiError(400, std::string("bad frame range: ") + e.what(), o.path(f::kFrames));
    }
  } else if (frames.is_array()) {
    if (frames.empty()) throw ApiError(400, "expected at least one frame", o.path(f::kFrames));
    for (size_t i = 0; i < frames.size(); ++i) {
      if (!frames[i].is_number_integer() || frames[i].get<int64_t>() < INT32_MIN ||
          frames[i].get<int64_t>() > INT32_MAX)
        throw ApiError(400, std::string("expected an integer frame, got ") + frames[i].dump(),
                       o.path(f::kFrames) + "/" + std::to_string(i));
      spec.frames.push_back(frames[i].get<int>());
    }
    std::sort(spec.frames.begin(), spec.frames.end());
    spec.frames.erase(std::unique(spec.frames.begin(), spec.frames.end()), spec.frames.end());
  } else {
    throw ApiError(400,
                   std::string("expected a frame range string (\"1-100\", \"1-100x5\", "
                               "\"1,5,9\") or an array of integers, got ") +
                       frames.type_name(),
                   o.path(f::kFrames));
  }
  spec.spp = int(o.integer(f::kSpp, spec.spp, 1, 1 << 20));
  spec.samples_per_task = int(o.integer(f::kSamplesPerTask, 0, 0, 1 << 20));
  spec.priority = int(o.integer(f::kPriority, spec.priority, -1000000, 1000000));
  spec.max_attempts = int(o.integer(f::kMaxAttempts, spec.max_attempts, 1, 100));
  if (o.has(f::kAssets)) spec.assets = read_assets(o.at(f::kAssets));
  const int64_t n = task_count(spec);
  if (n > kMaxTasksPerJob)
    throw ApiError(400,
                   "the job splits into " + std::to_string(n) + " tasks, more than " +
                       std::to_string(kMaxTasksPerJob) +
                       " (fewer frames or a larger samples_per_task)",
                   spec.samples_per_task > 0 ? o.path(f::kSamplesPerTask) : o.path(f::kFrames));
  return spec;
}

protocol::RegisterRequest read_register_request(const json& body) {
  const JsonObject o(body, "", {f::kName});
  protocol::RegisterRequest r{o.string(f::kName)};
  if (r.name.size() > 128) throw ApiError(400, "name longer than 128 characters", o.path(f::kName));
  return r;
}

protocol::LeaseRequest read_lease_request(const json& body) {
  const JsonObject o(body, "", {f::kWorkerId, f::kRenderer});
  protocol::LeaseRequest r{o.string(f::kWorkerId), o.opt_string(f::kRenderer).value_or("")};
  if (!r.renderer.empty() && !is_sha256_hex(r.renderer))
    throw ApiError(400, "expected the renderer's sha256 (64 lower-case hex digits)",
                   o.path(f::kRenderer));
  return r;
}

protocol::HeartbeatRequest read_heartbeat_request(const json& body) {
  const JsonObject o(body, "", {f::kLeaseId, f::kProgress});
  return {o.string(f::kLeaseId), o.number(f::kProgress, 0, 0, 1)};
}

protocol::CompleteRequest read_complete_request(const json& body) {
  const JsonObject o(body, "", {f::kLeaseId, f::kResult});
  protocol::CompleteRequest r{o.string(f::kLeaseId), o.string(f::kResult)};
  if (!is_sha256_hex(r.result))
    throw ApiError(400,
                   "expected the SHA-256 of the uploaded result blob (64 lower-case hex digits)",
                   o.path(f::kResult));
  return r;
}

protocol::FailRequest read_fail_request(const json& body) {
  const JsonObject o(body, "", {f::kLeaseId, f::kLog});
  return {o.string(f::kLeaseId), o.opt_string(f::kLog).value_or("")};
}

}  // namespace vesper
