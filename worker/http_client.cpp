#include "worker/http_client.h"

#include <curl/curl.h>

#include <cstdio>
#include <mutex>
#include <stdexcept>

namespace vesper::worker_detail {
namespace {

void global_init() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

size_t write_string(char* p, size_t size, size_t n, void* user) {
  static_cast<std::string*>(user)->append(p, size * n);
  return size * n;
}
size_t write_file(char* p, size_t size, size_t n, void* user) {
  return std::fwrite(p, 1, size * n, static_cast<std::FILE*>(user));
}

struct Headers {
  curl_slist* list = nullptr;
  ~Headers() { curl_slist_free_all(list); }
  void add(const std::string& h) {
    if (!h.empty()) list = curl_slist_append(list, h.c_str());
  }
};

// Resets the reused handle for a request to `url` (libcurl copies it) with
// `headers`, which must outlive the transfer.
CURL* start(void* handle, const std::string& url, const Headers& headers) {
  CURL* c = static_cast<CURL*>(handle);
  curl_easy_reset(c);
  curl_easy_setopt(c, CURLOPT_URL, url.c_str());
  curl_easy_setopt(c, CURLOPT_HTTPHEADER, headers.list);
  return c;
}

}  // namespace

HttpClient::HttpClient(std::string base_url, std::string token, double timeout_seconds)
    : base_(std::move(base_url)),
      auth_header_(token.empty() ? std::string() : "Authorization: Bearer " + token),
      timeout_(timeout_seconds) {
  while (!base_.empty() && base_.back() == '/') base_.pop_back();
  global_init();
  curl_ = curl_easy_init();
  if (!curl_) throw std::runtime_error("curl_easy_init failed");
}

HttpClient::~HttpClient() { curl_easy_cleanup(static_cast<CURL*>(curl_)); }

HttpResponse HttpClient::perform() {
  CURL* c = static_cast<CURL*>(curl_);
  HttpResponse r;
  char err[CURL_ERROR_SIZE] = {0};
  curl_easy_setopt(c, CURLOPT_ERRORBUFFER, err);
  curl_easy_setopt(c, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(c, CURLOPT_CONNECTTIMEOUT_MS, 10000L);
  curl_easy_setopt(c, CURLOPT_TIMEOUT_MS, long(timeout_ * 1000));
  const CURLcode rc = curl_easy_perform(c);
  if (rc != CURLE_OK) {
    r.error = err[0] ? err : curl_easy_strerror(rc);
    return r;
  }
  curl_easy_getinfo(c, CURLINFO_RESPONSE_CODE, &r.status);
  return r;
}

// Performs the prepared request, collecting the answer's body.
HttpResponse HttpClient::perform_to_string() {
  CURL* c = static_cast<CURL*>(curl_);
  std::string body;
  curl_easy_setopt(c, CURLOPT_WRITEFUNCTION, write_string);
  curl_easy_setopt(c, CURLOPT_WRITEDATA, &body);
  HttpResponse r = perform();
  r.body = std::move(body);
  return r;
}

HttpResponse HttpClient::post_json(const std::string& path, const std::string& json_body) {
  Headers h;
  h.add(auth_header_);
  h.add("Content-Type: application/json");
  CURL* c = start(curl_, base_ + path, h);
  curl_easy_setopt(c, CURLOPT_POSTFIELDS, json_body.data());
  curl_easy_setopt(c, CURLOPT_POSTFIELDSIZE_LARGE, curl_off_t(json_body.size()));
  return perform_to_string();
}

HttpResponse HttpClient::head(const std::string& path) {
  Headers h;
  h.add(auth_header_);
  CURL* c = start(curl_, base_ + path, h);
  curl_easy_setopt(c, CURLOPT_NOBODY, 1L);
  return perform();
}

HttpResponse HttpClient::del(const std::string& path) {
  Headers h;
  h.add(auth_header_);
  CURL* c = start(curl_, base_ + path, h);
  curl_easy_setopt(c, CURLOPT_CUSTOMREQUEST, "DELETE");
  return perform_to_string();
}

HttpResponse HttpClient::get(const std::string& path) {
  Headers h;
  h.add(auth_header_);
  start(curl_, base_ + path, h);
  return perform_to_string();
}

HttpResponse HttpClient::get_to_file(const std::string& path, const std::filesystem::path& file) {
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) {
    HttpResponse r;
    r.error = "cannot write " + file.string();
    return r;
  }
  Headers h;
  h.add(auth_header_);
  CURL* c = start(curl_, base_ + path, h);
  curl_easy_setopt(c, CURLOPT_WRITEFUNCTION, write_file);
  curl_easy_setopt(c, CURLOPT_WRITEDATA, f);
  HttpResponse r = perform();
  if (std::fclose(f) != 0 && r.status) r.error = "cannot write " + file.string();
  return r;
}

HttpResponse HttpClient::put_file(const std::string& path, const std::filesystem::path& file) {
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) {
    HttpResponse r;
    r.error = "cannot read " + file.string();
    return r;
  }
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  Headers h;
  h.add(auth_header_);
  h.add("Content-Type: application/octet-stream");
  h.add("Expect:");  // no 100-continue round trip
  CURL* c = start(curl_, base_ + path, h);
  curl_easy_setopt(c, CURLOPT_UPLOAD, 1L);
  curl_easy_setopt(c, CURLOPT_READDATA, f);  // default read function: fread
  curl_easy_setopt(c, CURLOPT_INFILESIZE_LARGE, curl_off_t(ec ? 0 : size));
  HttpResponse r = perform_to_string();
  std::fclose(f);
  return r;
}

}  // namespace vesper::worker_detail
