#include "worker/server_api.h"

#include <nlohmann/json.hpp>

namespace vesper::worker_detail {
namespace {

using nlohmann::json;

constexpr const char* kApi = "/api/v1";

std::string api(const std::string& path) { return kApi + path; }

}  // namespace

std::string describe(const HttpResponse& r) {
  if (r.status == 0) return "transport error: " + r.error;
  std::string msg = "HTTP " + std::to_string(r.status);
  const json j = json::parse(r.body, nullptr, false);
  if (j.is_object() && j.contains("error") && j["error"].is_string())
    msg += ": " + j["error"].get<std::string>();
  return msg;
}

ServerApi::ServerApi(const std::string& server_url, const std::string& token)
    : http_(server_url, token) {}

HttpResponse ServerApi::register_worker(const std::string& name) {
  return http_.post_json(api("/workers/register"), json{{"name", name}}.dump());
}

HttpResponse ServerApi::lease(const std::string& worker_id, const std::string& renderer_id) {
  json body{{"worker_id", worker_id}};
  if (!renderer_id.empty()) body["renderer"] = renderer_id;
  return http_.post_json(api("/lease"), body.dump());
}

HttpResponse ServerApi::heartbeat(const std::string& lease_id, double progress) {
  return http_.post_json(api("/heartbeat"),
                         json{{"lease_id", lease_id}, {"progress", progress}}.dump());
}

HttpResponse ServerApi::fail(const std::string& lease_id, const std::string& log) {
  return http_.post_json(api("/fail"), json{{"lease_id", lease_id}, {"log", log}}.dump());
}

HttpResponse ServerApi::complete(const std::string& lease_id, const std::string& result_blob) {
  return http_.post_json(api("/complete"),
                         json{{"lease_id", lease_id}, {"result", result_blob}}.dump());
}

HttpResponse ServerApi::download_blob(const std::string& blob, const std::filesystem::path& file) {
  return http_.get_to_file(api("/blobs/" + blob), file);
}

HttpResponse ServerApi::upload_blob(const std::string& blob, const std::filesystem::path& file) {
  return http_.put_file(api("/blobs/" + blob), file);
}

}  // namespace vesper::worker_detail
