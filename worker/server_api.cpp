#include "worker/server_api.h"

#include <nlohmann/json.hpp>

#include "protocol/error_body.h"
#include "protocol/paths.h"

namespace vesper::worker_detail {

namespace paths = protocol::paths;
using nlohmann::json;

std::string describe(const HttpResponse& r) {
  if (r.status == 0) return "transport error: " + r.error;
  std::string msg = "HTTP " + std::to_string(r.status);
  try {
    msg += ": " + json::parse(r.body).get<protocol::ErrorBody>().error;
  } catch (const json::exception&) {
    // No error body (a proxy's page, an empty answer): the status says it all.
  }
  return msg;
}

ServerApi::ServerApi(const std::string& server_url, const std::string& token)
    : http_(server_url, token) {}

HttpResponse ServerApi::register_worker(const protocol::RegisterRequest& request) {
  return http_.post_json(protocol::api(paths::kWorkerRegister), json(request).dump());
}

HttpResponse ServerApi::lease(const protocol::LeaseRequest& request) {
  return http_.post_json(protocol::api(paths::kLease), json(request).dump());
}

HttpResponse ServerApi::heartbeat(const protocol::HeartbeatRequest& request) {
  return http_.post_json(protocol::api(paths::kHeartbeat), json(request).dump());
}

HttpResponse ServerApi::fail(const protocol::FailRequest& request) {
  return http_.post_json(protocol::api(paths::kFail), json(request).dump());
}

HttpResponse ServerApi::complete(const protocol::CompleteRequest& request) {
  return http_.post_json(protocol::api(paths::kComplete), json(request).dump());
}

HttpResponse ServerApi::download_blob(const std::string& blob, const std::filesystem::path& file) {
  return http_.get_to_file(protocol::api(protocol::blob_path(blob)), file);
}

HttpResponse ServerApi::upload_blob(const std::string& blob, const std::filesystem::path& file) {
  return http_.put_file(protocol::api(protocol::blob_path(blob)), file);
}

}  // namespace vesper::worker_detail
