#pragma once
// The HTTP API: routes come from protocol::kRoutes, each served by the
// handler of its endpoint. From the request head alone, before any body
// byte is read: no route → 404, the route's bearer token missing or wrong →
// 401, a POST/PUT without Content-Length → 411, a body over its limit
// (max_json_bytes for POST, max_blob_bytes for PUT) → 413. An ApiError thrown
// by a handler becomes {"error", "path"} with its status. Connections,
// deadlines and the bound on concurrent requests are http_connections.*.
#include <memory>
#include <string>

#include "server/http_exchange.h"

namespace vesper {

struct ServerConfig;
class TokenFile;
class ServerCounters;

class HttpApi {
 public:
  HttpApi(const ServerConfig& config, TokenFile& tokens, ServerCounters& counters);
  ~HttpApi();  // stops
  HttpApi(const HttpApi&) = delete;
  HttpApi& operator=(const HttpApi&) = delete;

  // Registers every route; throws std::logic_error if an endpoint has no handler.
  void route(const HandlerTable& handlers);
  // Binds config.host:config.port (0: an ephemeral port) and returns the
  // port; throws if it cannot.
  int bind();
  // Serves on a background thread; returns once it accepts connections.
  void serve();
  // Stops serving and waits for the thread; idempotent.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vesper
