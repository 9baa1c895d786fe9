#include "server/http_exchange.h"

#include <cstdint>
#include <nlohmann/json.hpp>

#include "common/utf8.h"
#include "server/api_error.h"

namespace vesper {

std::string ApiRequest::query_value(const std::string& key) const {
  auto it = query.find(key);
  return it == query.end() ? std::string() : it->second;
}

ApiResponse json_response(int status, const nlohmann::json& body) {
  ApiResponse r;
  r.status = status;
  // Text from outside (a merge's stderr) may hold bytes that are not UTF-8:
  // replaced rather than thrown about.
  r.body = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  r.content_type = "application/json";
  return r;
}

ApiResponse text_response(std::string text, std::string content_type) {
  ApiResponse r;
  r.body = std::move(text);
  r.content_type = std::move(content_type);
  return r;
}

ApiResponse file_response(std::filesystem::path path, std::uintmax_t size,
                          std::string content_type) {
  ApiResponse r;
  r.content_type = std::move(content_type);
  r.file = ApiResponse::File{std::move(path), size};
  return r;
}

int64_t id_param(const ApiRequest& req, size_t index) {
  const std::string& s = req.params.at(index);
  try {
    size_t used = 0;
    const long long v = std::stoll(s, &used);
    if (used == s.size() && v > 0) return v;
  } catch (const std::exception&) {
  }
  throw ApiError(404, "no such id '" + utf8_safe(s, 80) + "'");
}

int frame_param(const ApiRequest& req, size_t index) {
  const std::string& s = req.params.at(index);
  try {
    size_t used = 0;
    const long long v = std::stoll(s, &used);
    if (used == s.size() && v >= INT32_MIN && v <= INT32_MAX) return int(v);
  } catch (const std::exception&) {
  }
  throw ApiError(404, "no such frame '" + utf8_safe(s, 80) + "'");
}

}  // namespace vesper
