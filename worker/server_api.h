#pragma once
// The worker's calls to the farm server, one per endpoint, with the paths
// and messages of the farm protocol (protocol/, docs/api/openapi.yaml).
// Answers come back as they are: each worker state decides what a status
// means for it (retry, register again, drop the task, give up), and reads a
// 200's body with the protocol's message types.
#include <filesystem>
#include <string>

#include "protocol/ops_messages.h"
#include "protocol/worker_messages.h"
#include "worker/http_client.h"

namespace vesper::worker_detail {

// "transport error: …" or "HTTP 409: <the server's error>", for logs.
std::string describe(const HttpResponse& r);

class ServerApi {
 public:
  ServerApi(const std::string& server_url, const std::string& token);

  HttpResponse register_worker(const protocol::RegisterRequest& request);
  HttpResponse goodbye(const protocol::GoodbyeRequest& request);
  HttpResponse lease(const protocol::LeaseRequest& request);
  HttpResponse heartbeat(const protocol::HeartbeatRequest& request);
  HttpResponse fail(const protocol::FailRequest& request);
  HttpResponse complete(const protocol::CompleteRequest& request);
  HttpResponse download_blob(const std::string& blob, const std::filesystem::path& file);
  HttpResponse upload_blob(const std::string& blob, const std::filesystem::path& file);

 private:
  HttpClient http_;
};

}  // namespace vesper::worker_detail
