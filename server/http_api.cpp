// Routes, auth and body limits over the connection layer (http_connections.*):
// every decision that does not need the body is taken from the request head,
// before a byte of the body is read.
#include "server/http_api.h"

#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "common/secret_token.h"
#include "common/utf8.h"
#include "protocol/error_body.h"
#include "server/api_error.h"
#include "server/http_connections.h"
#include "server/metrics.h"
#include "server/monitor_auth.h"
#include "server/server.h"
#include "server/tokens.h"

namespace vesper {
namespace {

using protocol::Method;
using protocol::Role;

// Messages may quote what the client sent (a path segment, a name): made
// valid UTF-8 first, or the JSON dump would throw and the answer be a 500.
ApiResponse error_with_path(int status, const std::string& message, const std::string& path) {
  ApiResponse r;
  r.status = status;
  r.body = nlohmann::json(protocol::ErrorBody{utf8_safe(message), utf8_safe(path)}).dump() + "\n";
  r.content_type = "application/json";
  return r;
}

std::string bearer(const RequestHead& req) {
  const std::string h = req.field("Authorization");
  constexpr std::string_view prefix = "Bearer ";
  if (h.size() <= prefix.size() || h.compare(0, prefix.size(), prefix) != 0) return {};
  return h.substr(prefix.size());
}

bool authorized(const RequestHead& req, Role role, TokenFile& token_file) {
  if (role == Role::None) return true;
  const std::string token = bearer(req);
  if (token.empty()) return false;
  // The file as it is now: a revoked token is refused without a restart.
  const std::shared_ptr<const Tokens> tokens = token_file.current();
  // Evaluate every comparison regardless, in constant time.
  const bool sub = constant_time_equal(token, tokens->submitter);
  const bool wrk = tokens->worker_allowed(token);
  switch (role) {
    case Role::Submitter:
      return sub;
    case Role::Worker:
      return wrk;
    case Role::Either:
      return sub || wrk;
    case Role::None:
      break;
  }
  return true;
}

enum class Access { Allowed, Refused, CookieWithoutHeader };

// The bearer token, else the monitor's session cookie (monitor_auth.h), else
// read-only viewing when configured.
Access access(const RequestHead& req, const protocol::Route& route, TokenFile& token_file,
              bool read_only) {
  if (authorized(req, route.role, token_file)) return Access::Allowed;
  if (!bearer(req).empty()) return Access::Refused;  // a wrong token is never overridden
  const std::string cookie = cookie_value(req.field("Cookie"), protocol::kSessionCookie);
  if (!cookie.empty() && cookie_may_authorize(route) &&
      constant_time_equal(cookie, session_value(token_file.current()->submitter))) {
    const bool reads = route.method == Method::Get;
    if (!reads && req.field(protocol::kMonitorHeader) != protocol::kMonitorHeaderValue)
      return Access::CookieWithoutHeader;
    return Access::Allowed;
  }
  if (read_only && route.method == Method::Get && read_only_viewable(route)) return Access::Allowed;
  return Access::Refused;
}

const char* token_name(Role role) {
  return role == Role::Submitter ? "submitter"
         : role == Role::Worker  ? "worker"
                                 : "submitter or worker";
}

// The request method a route is registered under; HEAD is answered by the
// GET route of the path (its answer without the body).
std::optional<Method> route_method(const std::string& method) {
  if (method == "GET" || method == "HEAD") return Method::Get;
  if (method == "POST") return Method::Post;
  if (method == "PUT") return Method::Put;
  if (method == "DELETE") return Method::Delete;
  return std::nullopt;
}

// Matches a decoded path against a route's template: a {parameter} is one
// non-empty path segment, except {sha256}, which takes the rest of the path —
// BlobStore answers 400 for any malformed name, so "../x" is refused rather
// than 404.
bool match(const std::string& pattern, const std::string& path, std::vector<std::string>& params) {
  size_t i = 0, j = 0;
  while (i < pattern.size()) {
    if (pattern[i] != '{') {
      if (j >= path.size() || path[j] != pattern[i]) return false;
      ++i, ++j;
      continue;
    }
    const size_t close = pattern.find('}', i);
    if (pattern.compare(i, close - i + 1, "{sha256}") == 0) {
      params.push_back(path.substr(j));
      j = path.size();
    } else {
      const size_t end = std::min(path.find('/', j), path.size());
      if (end == j) return false;
      params.push_back(path.substr(j, end - j));
      j = end;
    }
    i = close + 1;
  }
  return j == path.size();
}

struct CompiledRoute {
  protocol::Route route;
  std::string pattern;
  Handler handler;
};

}  // namespace

struct HttpApi::Impl {
  Impl(const ServerConfig& c, TokenFile& t, ServerCounters& n)
      : config(c),
        tokens(t),
        counters(n),
        connections(
            ConnectionLimits{c.max_connections, c.threads, c.header_timeout, c.max_header_bytes,
                             c.idle_timeout, c.io_timeout},
            [this](const RequestHead& h) { return admit(h); },
            [this](int status) { counters.response(status); }) {}

  const ServerConfig& config;
  TokenFile& tokens;
  ServerCounters& counters;
  std::vector<CompiledRoute> routes;
  HttpConnections connections;  // last: stopped before the routes go

  // Everything decided from the head: route (404), token (401), a body
  // route's Content-Length (411) and its limit (413).
  Admission admit(const RequestHead& h) {
    const std::optional<Method> method = route_method(h.method);
    const CompiledRoute* found = nullptr;
    std::vector<std::string> params;
    for (const CompiledRoute& r : routes) {
      if (!method || r.route.method != *method) continue;
      params.clear();
      if (match(r.pattern, h.path, params)) {
        found = &r;
        break;
      }
    }
    if (!found) return {error_response(404, "no such endpoint: " + h.method + " " + h.path), {}};
    const Role role = found->route.role;
    const Access a = access(h, found->route, tokens, config.monitor_read_only);
    if (a == Access::CookieWithoutHeader)
      return {error_response(403,
                             "a request authorised by the monitor's session cookie must "
                             "carry the header " +
                                 std::string(protocol::kMonitorHeader) + ": " +
                                 std::string(protocol::kMonitorHeaderValue)),
              {}};
    if (a == Access::Refused) {
      ApiResponse r = error_response(
          401, std::string("missing or wrong bearer token (this endpoint needs the ") +
                   token_name(role) +
                   " token from the server's tokens.json; a revoked or disabled token is refused)");
      r.headers.emplace_back("WWW-Authenticate", "Bearer");
      return {std::move(r), {}};
    }
    const bool blob = *method == Method::Put;
    if ((blob || *method == Method::Post) && !h.has_content_length)
      return {error_response(411, "a " + h.method + " request needs a Content-Length header"), {}};
    const size_t limit = blob ? config.max_blob_bytes : config.max_json_bytes;
    if (h.content_length > limit)
      return {error_response(413, std::string(blob ? "request body" : "JSON body") + " of " +
                                      std::to_string(h.content_length) +
                                      " bytes exceeds the limit of " + std::to_string(limit) +
                                      " bytes"),
              {}};
    return {std::nullopt,
            [this, found, params = std::move(params), query = h.query, head = h.method == "HEAD",
             what = h.method + " " + h.path](const std::string& body) {
              try {
                return found->handler(ApiRequest{body, params, query, head});
              } catch (const ApiError& e) {
                return error_with_path(e.status(), e.what(), e.path());
              } catch (const std::exception& e) {
                spdlog::error("{}: {}", what, e.what());
                return error_response(500, std::string("internal error: ") + e.what());
              }
            }};
  }
};

HttpApi::HttpApi(const ServerConfig& config, TokenFile& tokens, ServerCounters& counters)
    : impl_(std::make_unique<Impl>(config, tokens, counters)) {}

HttpApi::~HttpApi() { stop(); }

void HttpApi::route(const HandlerTable& handlers) {
  for (const protocol::Route& r : protocol::kRoutes) {
    auto it = handlers.find(r.endpoint);
    if (it == handlers.end() || !it->second)
      throw std::logic_error("server: no handler for " + std::string(to_string(r.method)) + " " +
                             protocol::full_path(r));
    if (r.method != Method::Head) impl_->routes.push_back({r, protocol::full_path(r), it->second});
  }
}

int HttpApi::bind() { return impl_->connections.bind(impl_->config.host, impl_->config.port); }

void HttpApi::serve() { impl_->connections.serve(); }

void HttpApi::stop() { impl_->connections.stop(); }

}  // namespace vesper
