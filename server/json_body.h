#pragma once
// Parsing and validating JSON request bodies. Every error is an ApiError 400
// naming the JSON path (RFC 6901 pointer such as "/frames") and what was
// expected there; unknown keys are rejected, so a typo ("sample_per_task")
// is an error rather than a silently ignored default.
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "jobs/job.h"

namespace vesper {

nlohmann::json parse_json_body(const std::string& body);

// A view of one JSON object in a request body.
class JsonObject {
 public:
  // Throws unless `j` is an object whose keys are all in `allowed`.
  JsonObject(const nlohmann::json& j, std::string path, std::initializer_list<const char*> allowed);

  bool has(const char* key) const;
  std::string path(const char* key) const { return path_ + "/" + key; }
  const nlohmann::json& at(const char* key) const;

  std::string string(const char* key) const;  // required, non-empty
  std::optional<std::string> opt_string(const char* key) const;
  int64_t integer(const char* key, int64_t def, int64_t min, int64_t max) const;  // optional
  double number(const char* key, double def, double min, double max) const;       // optional

 private:
  const nlohmann::json& j_;
  std::string path_;
};

// A submitted job: {"name", "scene", "frames", "spp", "samples_per_task",
// "priority", "max_attempts", "assets"}. `frames` is a frame-range string ("1-10x2",
// "1,5,9") or an array of integers; `scene` must be a SHA-256 (the existence
// of the blob is checked by the server). Limits: spp <= 1<<20, at most
// kMaxTasksPerJob tasks.
constexpr int64_t kMaxTasksPerJob = 100000;
constexpr int64_t kMaxAssetsPerJob = 10000;
// "assets": [{"name": "assets/cube.obj", "blob": "<sha256>"}, ...]: names are
// checked by asset_name_problem (jobs/job.h), unique, not "scene.json", and
// no name is the directory of another; blobs are SHA-256 spellings (their
// existence is checked by the server). Errors name "/assets/3/name" etc.
std::vector<Asset> parse_assets(const nlohmann::json& assets);
JobSpec parse_job_request(const nlohmann::json& body);
// Tasks `spec` splits into (what the store will create).
int64_t task_count(const JobSpec& spec);

}  // namespace vesper
