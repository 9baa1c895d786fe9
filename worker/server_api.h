#pragma once
// The worker's calls to the farm server (server/README.md), one per endpoint.
// Answers come back as they are: each worker state decides what a status
// means for it (retry, register again, drop the task, give up).
#include <filesystem>
#include <string>

#include "worker/http_client.h"

namespace vesper::worker_detail {

// "transport error: …" or "HTTP 409: <the server's error>", for logs.
std::string describe(const HttpResponse& r);

class ServerApi {
 public:
  ServerApi(const std::string& server_url, const std::string& token);

  HttpResponse register_worker(const std::string& name);
  // `renderer_id` (sha256 of the renderer) may be empty: no result reuse.
  HttpResponse lease(const std::string& worker_id, const std::string& renderer_id);
  HttpResponse heartbeat(const std::string& lease_id, double progress);
  HttpResponse fail(const std::string& lease_id, const std::string& log);
  HttpResponse complete(const std::string& lease_id, const std::string& result_blob);
  HttpResponse download_blob(const std::string& blob, const std::filesystem::path& file);
  HttpResponse upload_blob(const std::string& blob, const std::filesystem::path& file);

 private:
  HttpClient http_;
};

}  // namespace vesper::worker_detail
