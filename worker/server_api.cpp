#include "worker/server_api.h"

#include <nlohmann/json.hpp>

#include "protocol/error_body.h"
#include "protocol/paths.h"

namespace vesper::worker_detail {

namespace paths = protocol::paths;
using nlohmann::json;

namespace {

// A request as JSON text. A failure log quotes the render's stderr, which may
// hold bytes that are not UTF-8: replaced, not thrown about.
std::string body(const json& request) {
  return request.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace

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
  return http_.post_json(protocol::api(paths::kWorkerRegister), body(request));
}

HttpResponse ServerApi::goodbye(const protocol::GoodbyeRequest& request) {
  return http_.post_json(protocol::api(paths::kWorkerGoodbye), body(request));
}

HttpResponse ServerApi::lease(const protocol::LeaseRequest& request) {
  return http_.post_json(protocol::api(paths::kLease), body(request));
}

HttpResponse ServerApi::heartbeat(const protocol::HeartbeatRequest& request) {
  return http_.post_json(protocol::api(paths::kHeartbeat), body(request));
}

HttpResponse ServerApi::fail(const protocol::FailRequest& request) {
  return http_.post_json(protocol::api(paths::kFail), body(request));
}

HttpResponse ServerApi::complete(const protocol::CompleteRequest& request) {
  return http_.post_json(protocol::api(paths::kComplete), body(request));
}

HttpResponse ServerApi::download_blob(const std::string& blob, const std::filesystem::path& file) {
  return http_.get_to_file(protocol::api(protocol::blob_path(blob)), file);
}

HttpResponse ServerApi::upload_blob(const std::string& blob, const std::filesystem::path& file) {
  return http_.put_file(protocol::api(protocol::blob_path(blob)), file);
}

}  // namespace vesper::worker_detail
