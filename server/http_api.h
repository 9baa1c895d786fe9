#pragma once
// The HTTP layer: routes, auth, size limits, JSON errors, sockets. Routes
// come from protocol::kRoutes, each served by the handler of its endpoint;
// a route's role decides which bearer token it needs (401 otherwise), POST
// bodies above max_json_bytes are 413, and an ApiError thrown by a handler
// becomes {"error", "path"} with its status. This file's .cpp is the only one
// that includes <httplib.h>.
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
