#pragma once
// A small blocking libcurl client for the worker protocol: JSON requests,
// blob PUT/GET, bearer token. One CURL handle per client (keep-alive); not
// thread-safe — the worker uses one per thread.
#include <cstddef>
#include <filesystem>
#include <string>

namespace vesper::worker_detail {

struct HttpResponse {
  long status = 0;  // 0 = transport error (see error)
  std::string body;
  std::string error;  // curl's message when status == 0
  bool ok() const { return status >= 200 && status < 300; }
};

class HttpClient {
 public:
  // base_url: "http://host:port"; paths given to the calls start with '/'
  // (or are empty: base_url is the whole URL). An empty token sends no
  // Authorization header (the server's webhook, server/job_webhook.h).
  HttpClient(std::string base_url, std::string token, double timeout_seconds = 60);
  ~HttpClient();
  HttpClient(const HttpClient&) = delete;
  HttpClient& operator=(const HttpClient&) = delete;

  HttpResponse post_json(const std::string& path, const std::string& json_body);
  HttpResponse put_file(const std::string& path, const std::filesystem::path& file);
  // GET into a file (streamed); the file is truncated first.
  HttpResponse get_to_file(const std::string& path, const std::filesystem::path& file);
  HttpResponse get(const std::string& path);
  HttpResponse head(const std::string& path);  // status only
  HttpResponse del(const std::string& path);   // DELETE, the answer's body kept

 private:
  HttpResponse perform();
  HttpResponse perform_to_string();
  std::string base_, auth_header_;
  double timeout_;
  void* curl_;
};

}  // namespace vesper::worker_detail
