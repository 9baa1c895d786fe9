#pragma once
// The submitter side of the farm API (server/README.md) for the CLI: where the
// server is, which token to send, and JSON calls whose errors carry the
// server's message. Built on the worker's libcurl client.
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/farm_config.h"
#include "protocol/job_messages.h"

namespace vesper::worker_detail {
class HttpClient;
}

namespace vesper::cli {

class FarmClientError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class TokenRole { Submitter, Worker };

// The server URL: `url` if given, else $VESPER_SERVER, else settings.worker.server.
std::string resolve_server_url(const FarmSettings& settings, const std::optional<std::string>& url);
// The token: `token` if given, else $VESPER_TOKEN (submitter) / $VESPER_WORKER_TOKEN
// (worker), else the tokens.json of the server at `server_url` if it runs on
// this machine (local_server.h), else of the settings' data dir.
// Throws FarmClientError saying where it looked.
std::string resolve_token(const FarmSettings& settings, const std::string& server_url,
                          const std::optional<std::string>& token, TokenRole role);

class FarmClient {
 public:
  FarmClient(std::string url, std::string token);
  ~FarmClient();
  FarmClient(const FarmClient&) = delete;
  FarmClient& operator=(const FarmClient&) = delete;

  const std::string& url() const { return url_; }
  // Paths are relative to protocol::kApiPrefix (give protocol::job_path(7),
  // "/jobs/7", not "/api/v1/jobs/7"); the answers' shapes are protocol/'s
  // messages (`get_json(path).get<protocol::JobDetail>()`). Non-2xx
  // answers throw FarmClientError "<METHOD> <path>: <status>: <server's error> (at <path>)".
  nlohmann::json get_json(const std::string& path);
  nlohmann::json post_json(const std::string& path, const nlohmann::json& body);
  std::string get_text(const std::string& path);
  nlohmann::json delete_json(const std::string& path);
  // GET /jobs/{id} with every page of its task list (protocol::kTasksAfterParam)
  // joined into one answer: the JSON, and as protocol::JobDetail.
  nlohmann::json get_job_json(int64_t job);
  protocol::JobDetail get_job(int64_t job);
  // Uploads a file as a blob unless the server has it; returns its sha256.
  std::string put_blob(const std::filesystem::path& file);
  // Streams a GET into `file` (written as file + ".part", renamed when complete).
  void download(const std::string& path, const std::filesystem::path& file);

 private:
  std::string url_;
  std::unique_ptr<worker_detail::HttpClient> http_;
};

}  // namespace vesper::cli
