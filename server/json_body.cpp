#include "server/json_body.h"

#include <algorithm>
#include <climits>
#include <set>

#include "common/sha256.h"
#include "jobs/frame_range.h"
#include "server/api_error.h"

namespace vesper {

using nlohmann::json;

json parse_json_body(const std::string& body) {
  try {
    return json::parse(body);
  } catch (const json::parse_error& e) {
    throw ApiError(400, std::string("request body is not valid JSON: ") + e.what(), "");
  }
}

namespace {
const char* type_name(const json& j) { return j.type_name(); }
// RFC 6901 escaping of one reference token.
std::string escape(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}
}  // namespace

JsonObject::JsonObject(const json& j, std::string path, std::initializer_list<const char*> allowed)
    : j_(j), path_(std::move(path)) {
  if (!j.is_object())
    throw ApiError(400, std::string("expected an object, got ") + type_name(j),
                   path_.empty() ? "" : path_);
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw ApiError(400, "unknown key '" + key + "' (expected one of: " + list + ")",
                     path_ + "/" + escape(key));
    }
  }
}

bool JsonObject::has(const char* key) const { return j_.contains(key); }

const json& JsonObject::at(const char* key) const {
  if (!has(key)) throw ApiError(400, std::string("missing required key '") + key + "'", path(key));
  return j_.at(key);
}

std::string JsonObject::string(const char* key) const {
  const json& v = at(key);
  if (!v.is_string())
    throw ApiError(400, std::string("expected a string, got ") + type_name(v), path(key));
  if (v.get_ref<const std::string&>().empty())
    throw ApiError(400, "expected a non-empty string", path(key));
  return v.get<std::string>();
}

std::optional<std::string> JsonObject::opt_string(const char* key) const {
  if (!has(key)) return std::nullopt;
  const json& v = j_.at(key);
  if (!v.is_string())
    throw ApiError(400, std::string("expected a string, got ") + type_name(v), path(key));
  return v.get<std::string>();
}

int64_t JsonObject::integer(const char* key, int64_t def, int64_t min, int64_t max) const {
  if (!has(key)) return def;
  const json& v = j_.at(key);
  if (!v.is_number_integer())
    throw ApiError(400, std::string("expected an integer, got ") + type_name(v), path(key));
  // Unsigned values above int64 range arrive as number_unsigned.
  if (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(max))
    throw ApiError(400,
                   "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                       "], got " + v.dump(),
                   path(key));
  const int64_t x = v.get<int64_t>();
  if (x < min || x > max)
    throw ApiError(400,
                   "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                       "], got " + std::to_string(x),
                   path(key));
  return x;
}

double JsonObject::number(const char* key, double def, double min, double max) const {
  if (!has(key)) return def;
  const json& v = j_.at(key);
  if (!v.is_number())
    throw ApiError(400, std::string("expected a number, got ") + type_name(v), path(key));
  const double x = v.get<double>();
  if (!(x >= min && x <= max))
    throw ApiError(400,
                   "expected a number in [" + std::to_string(min) + ", " + std::to_string(max) +
                       "], got " + v.dump(),
                   path(key));
  return x;
}

int64_t task_count(const JobSpec& spec) {
  const int64_t split = spec.samples_per_task > 0 ? spec.samples_per_task : spec.spp;
  return int64_t(spec.frames.size()) * ((spec.spp + split - 1) / split);
}

std::vector<Asset> parse_assets(const json& assets) {
  if (!assets.is_array())
    throw ApiError(
        400,
        std::string("expected an array of {\"name\", \"blob\"} objects, got ") + assets.type_name(),
        "/assets");
  if (assets.size() > size_t(kMaxAssetsPerJob))
    throw ApiError(400, "more than " + std::to_string(kMaxAssetsPerJob) + " assets", "/assets");
  std::vector<Asset> out;
  std::set<std::string> names, dirs;  // dirs: every directory some name needs
  for (size_t i = 0; i < assets.size(); ++i) {
    const std::string at = "/assets/" + std::to_string(i);
    const JsonObject a(assets[i], at, {"name", "blob"});
    Asset asset;
    const json& name = a.at("name");
    if (!name.is_string())
      throw ApiError(400, std::string("expected a string, got ") + name.type_name(), at + "/name");
    asset.name = name.get<std::string>();
    std::string shown = asset.name.substr(0, 80);
    for (char& c : shown)
      if (static_cast<unsigned char>(c) < 0x20) c = '?';
    if (const std::string why = asset_name_problem(asset.name); !why.empty())
      throw ApiError(400, "asset name '" + shown + "' " + why, at + "/name");
    if (asset.name == "scene.json")
      throw ApiError(400, "asset name 'scene.json' is reserved for the scene itself", at + "/name");
    if (!names.insert(asset.name).second)
      throw ApiError(400, "duplicate asset name '" + shown + "'", at + "/name");
    for (size_t slash = asset.name.find('/'); slash != std::string::npos;
         slash = asset.name.find('/', slash + 1))
      dirs.insert(asset.name.substr(0, slash));
    const json& blob = a.at("blob");
    if (!blob.is_string() || !is_sha256_hex(blob.get<std::string>()))
      throw ApiError(400,
                     "expected the SHA-256 of an uploaded blob (64 lower-case hex digits), got " +
                         blob.dump().substr(0, 80),
                     at + "/blob");
    asset.blob = blob.get<std::string>();
    out.push_back(std::move(asset));
  }
  // A name cannot be a file and a directory at once ("a" and "a/b").
  for (size_t i = 0; i < out.size(); ++i)
    if (dirs.count(out[i].name))
      throw ApiError(
          400,
          "asset name '" + out[i].name.substr(0, 80) + "' is also the directory of another asset",
          "/assets/" + std::to_string(i) + "/name");
  return out;
}

JobSpec parse_job_request(const json& body) {
  const JsonObject o(
      body, "",
      {"name", "scene", "frames", "spp", "samples_per_task", "priority", "max_attempts", "assets"});
  JobSpec spec;
  spec.name = o.opt_string("name").value_or("job");
  if (spec.name.size() > 256) throw ApiError(400, "name longer than 256 characters", "/name");
  spec.scene = o.string("scene");
  if (!is_sha256_hex(spec.scene))
    throw ApiError(400,
                   "expected the SHA-256 of an uploaded scene blob (64 lower-case hex digits), "
                   "got '" +
                       spec.scene.substr(0, 80) + "'",
                   "/scene");
  const json& frames = o.at("frames");
  if (frames.is_string()) {
    try {
      spec.frames = parse_frame_range(frames.get<std::string>());
    } catch (const FrameRangeError& e) {
      throw ApiError(400, std::string("bad frame range: ") + e.what(), "/frames");
    }
  } else if (frames.is_array()) {
    if (frames.empty()) throw ApiError(400, "expected at least one frame", "/frames");
    for (size_t i = 0; i < frames.size(); ++i) {
      if (!frames[i].is_number_integer() || frames[i].get<int64_t>() < INT32_MIN ||
          frames[i].get<int64_t>() > INT32_MAX)
        throw ApiError(400, std::string("expected an integer frame, got ") + frames[i].dump(),
                       "/frames/" + std::to_string(i));
      spec.frames.push_back(frames[i].get<int>());
    }
    std::sort(spec.frames.begin(), spec.frames.end());
    spec.frames.erase(std::unique(spec.frames.begin(), spec.frames.end()), spec.frames.end());
  } else {
    throw ApiError(400,
                   std::string("expected a frame range string (\"1-100\", \"1-100x5\", "
                               "\"1,5,9\") or an array of integers, got ") +
                       frames.type_name(),
                   "/frames");
  }
  spec.spp = int(o.integer("spp", spec.spp, 1, 1 << 20));
  spec.samples_per_task = int(o.integer("samples_per_task", 0, 0, 1 << 20));
  spec.priority = int(o.integer("priority", spec.priority, -1000000, 1000000));
  spec.max_attempts = int(o.integer("max_attempts", spec.max_attempts, 1, 100));
  if (o.has("assets")) spec.assets = parse_assets(o.at("assets"));
  const int64_t n = task_count(spec);
  if (n > kMaxTasksPerJob)
    throw ApiError(400,
                   "the job splits into " + std::to_string(n) + " tasks, more than " +
                       std::to_string(kMaxTasksPerJob) +
                       " (fewer frames or a larger samples_per_task)",
                   spec.samples_per_task > 0 ? "/samples_per_task" : "/frames");
  return spec;
}

}  // namespace vesper
