#pragma once
// What a handler sees of an HTTP exchange, without the wire: the request's
// body, path parameters and query; the response's status, body and headers,
// or a file streamed as its body. http_api.cpp routes to the handlers and
// turns an ApiError thrown by one into the JSON error answer;
// http_connections.cpp writes the response.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "protocol/routes.h"

namespace vesper {

struct ApiRequest {
  const std::string& body;
  std::vector<std::string> params;                // path parameters, in template order
  std::multimap<std::string, std::string> query;  // ?key=value
  bool head = false;                              // a HEAD request (answered by its GET route)

  // The query value of `key`, or "" when it is absent.
  std::string query_value(const std::string& key) const;
};

struct ApiResponse {
  int status = 200;
  std::string body;  // empty with an empty content_type: no body (204)
  std::string content_type;
  std::vector<std::pair<std::string, std::string>> headers;
  struct File {
    std::filesystem::path path;
    std::uintmax_t size = 0;
  };
  std::optional<File> file;  // streamed as the body instead of `body`
};

// `body` as "<json>\n", application/json.
ApiResponse json_response(int status, const nlohmann::json& body);
ApiResponse text_response(std::string text, std::string content_type);
ApiResponse file_response(std::filesystem::path path, std::uintmax_t size,
                          std::string content_type);

using Handler = std::function<ApiResponse(const ApiRequest&)>;
// One handler per endpoint of protocol::kRoutes.
using HandlerTable = std::map<protocol::Endpoint, Handler>;

// Path parameters: a positive id, a frame number (ApiError 404 otherwise:
// no such resource).
int64_t id_param(const ApiRequest& req, size_t index);
int frame_param(const ApiRequest& req, size_t index);

}  // namespace vesper
