// The only file that includes cpp-httplib.
#include "server/http_api.h"

#include <httplib.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/secret_token.h"
#include "common/utf8.h"
#include "protocol/error_body.h"
#include "server/api_error.h"
#include "server/metrics.h"
#include "server/server.h"
#include "server/tokens.h"

namespace vesper {
namespace {

using protocol::Role;

// Messages may quote what the client sent (a path segment, a name): made
// valid UTF-8 first, or the JSON dump would throw and the answer be a 500.
void send_error(httplib::Response& res, int status, const std::string& message,
                const std::string& path = {}) {
  res.status = status;
  res.set_content(
      nlohmann::json(protocol::ErrorBody{utf8_safe(message), utf8_safe(path)}).dump() + "\n",
      "application/json");
}

// An error answer after which the connection is closed, its unread bytes
// never parsed as a next request. cpp-httplib 0.11 keeps a connection open
// whatever the handler says, but drops it when a content provider fails:
// this one sends the whole body, then reports failure.
void send_error_and_close(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_header("Connection", "close");
  const std::string body =
      nlohmann::json(protocol::ErrorBody{utf8_safe(message), {}}).dump() + "\n";
  res.set_content_provider(body.size(), "application/json",
                           [body](size_t offset, size_t, httplib::DataSink& sink) {
                             sink.write(body.data() + offset, body.size() - offset);
                             return false;
                           });
}

// Streams a file as the response body.
void send_file(httplib::Response& res, const ApiResponse::File& file, const std::string& type) {
  res.set_content_provider(size_t(file.size), type,
                           [path = file.path, in = std::shared_ptr<std::ifstream>()](
                               size_t offset, size_t length, httplib::DataSink& sink) mutable {
                             if (!in) {
                               in = std::make_shared<std::ifstream>(path, std::ios::binary);
                               if (!*in) return false;
                             }
                             std::string buf(std::min<size_t>(length, 1 << 20), '\0');
                             in->seekg(std::streamoff(offset));
                             in->read(buf.data(), std::streamsize(buf.size()));
                             const auto n = size_t(in->gcount());
                             if (n == 0) return false;
                             return sink.write(buf.data(), n);
                           });
}

void send(httplib::Response& res, const ApiResponse& r) {
  res.status = r.status;
  for (const auto& [name, value] : r.headers) res.set_header(name, value);
  if (r.file)
    send_file(res, *r.file, r.content_type);
  else if (!r.body.empty() || !r.content_type.empty())
    res.set_content(r.body, r.content_type);
}

std::string bearer(const httplib::Request& req) {
  const std::string h = req.get_header_value("Authorization");
  constexpr std::string_view prefix = "Bearer ";
  if (h.size() <= prefix.size() || h.compare(0, prefix.size(), prefix) != 0) return {};
  return h.substr(prefix.size());
}

bool authorized(const httplib::Request& req, Role role, TokenFile& token_file) {
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

const char* token_name(Role role) {
  return role == Role::Submitter ? "submitter"
         : role == Role::Worker  ? "worker"
                                 : "submitter or worker";
}

// The route's path template as cpp-httplib's regex: a {parameter} is one path
// segment, except {sha256}, which takes the rest of the path — BlobStore
// answers 400 for any malformed name, so "../x" is refused rather than 404.
std::string pattern_of(const protocol::Route& r) {
  const std::string path = protocol::full_path(r);
  std::string out;
  for (size_t i = 0; i < path.size(); ++i) {
    if (path[i] != '{') {
      out += path[i];
      continue;
    }
    const size_t close = path.find('}', i);
    out += path.compare(i, close - i + 1, "{sha256}") == 0 ? "(.*)" : "([^/]+)";
    i = close;
  }
  return out;
}

}  // namespace

struct HttpApi::Impl {
  Impl(const ServerConfig& c, TokenFile& t, ServerCounters& n)
      : config(c), tokens(t), counters(n) {}

  const ServerConfig& config;
  TokenFile& tokens;
  ServerCounters& counters;
  httplib::Server http;
  std::thread thread;
  int listen_socket = -1;  // set by the socket options callback, before bind

  httplib::Server::Handler wrap(const protocol::Route& route, Handler h) {
    const bool json_body = route.method == protocol::Method::Post;
    return [this, role = route.role, json_body, h = std::move(h)](const httplib::Request& req,
                                                                  httplib::Response& res) {
      if (!authorized(req, role, tokens)) {
        res.set_header("WWW-Authenticate", "Bearer");
        send_error(
            res, 401,
            std::string("missing or wrong bearer token (this endpoint needs the ") +
                token_name(role) +
                " token from the server's tokens.json; a revoked or disabled token is refused)");
        return;
      }
      if (json_body && req.body.size() > config.max_json_bytes) {
        send_error(res, 413,
                   "JSON body of " + std::to_string(req.body.size()) +
                       " bytes exceeds the limit of " + std::to_string(config.max_json_bytes));
        return;
      }
      try {
        ApiRequest api{req.body, {}, req.params};
        for (size_t i = 1; i < req.matches.size(); ++i) api.params.push_back(req.matches[i]);
        send(res, h(api));
      } catch (const ApiError& e) {
        send_error(res, e.status(), e.what(), e.path());
      } catch (const std::exception& e) {
        spdlog::error("{} {}: {}", req.method, req.path, e.what());
        send_error(res, 500, std::string("internal error: ") + e.what());
      }
    };
  }

  void add(const protocol::Route& route, const Handler& h) {
    const std::string pattern = pattern_of(route);
    switch (route.method) {
      case protocol::Method::Get:
        http.Get(pattern, wrap(route, h));
        break;
      case protocol::Method::Post:
        http.Post(pattern, wrap(route, h));
        break;
      case protocol::Method::Put:
        http.Put(pattern, wrap(route, h));
        break;
      case protocol::Method::Head:
        break;  // cpp-httplib answers HEAD with the GET route of the path
    }
  }

  void install_hooks() {
    // Before the body is read: a request whose length is ambiguous (two
    // Content-Length headers, which cpp-httplib would resolve by taking the
    // first, or one beside Transfer-Encoding) is how requests are smuggled
    // past a proxy. Refused, and the connection closed, as RFC 9112 says.
    http.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
      const size_t lengths = req.get_header_value_count("Content-Length");
      if (lengths <= 1 && !(lengths == 1 && req.has_header("Transfer-Encoding")))
        return httplib::Server::HandlerResponse::Unhandled;
      send_error_and_close(res, 400,
                           lengths > 1 ? "more than one Content-Length header"
                                       : "both Content-Length and Transfer-Encoding headers");
      return httplib::Server::HandlerResponse::Handled;
    });
    // JSON bodies for errors produced by httplib itself (404 no route, 413
    // over the payload limit, 400 unparsable request).
    http.set_error_handler(httplib::Server::HandlerWithResponse([this](const httplib::Request& req,
                                                                       httplib::Response& res) {
      if (!res.body.empty() || res.get_header_value("Connection") == "close")
        return httplib::Server::HandlerResponse::Unhandled;
      std::string msg = res.status == 404   ? "no such endpoint: " + req.method + " " + req.path
                        : res.status == 413 ? "request body exceeds the limit of " +
                                                  std::to_string(config.max_blob_bytes) + " bytes"
                                            : "HTTP " + std::to_string(res.status);
      send_error(res, res.status, msg);
      return httplib::Server::HandlerResponse::Handled;
    }));
    // Counted before the response is written (the logger runs after it), so
    // a client that got an answer sees it in the next /metrics.
    http.set_post_routing_handler(
        [this](const httplib::Request&, httplib::Response& res) { counters.response(res.status); });
    http.set_logger([](const httplib::Request& req, const httplib::Response& res) {
      spdlog::debug("{} {} -> {}", req.method, req.path, res.status);
    });
  }

  void configure() {
    const int threads = config.threads < 1 ? 1 : config.threads;
    http.new_task_queue = [threads] { return new httplib::ThreadPool(size_t(threads)); };
    http.set_payload_max_length(config.max_blob_bytes);
    http.set_keep_alive_timeout(5);
    // Responses go out as headers + body; without TCP_NODELAY the body waits
    // for the client's delayed ACK (~40 ms per keep-alive request,
    // vesper_farm_bench).
    http.set_tcp_nodelay(true);
    http.set_read_timeout(30);
    http.set_write_timeout(30);
    // Not cpp-httplib's default options: those set SO_REUSEPORT, which lets a
    // second server bind the same port and silently take half the requests.
    // SO_REUSEADDR alone still allows a restart over TIME_WAIT connections.
    http.set_socket_options([this](int sock) {
      int yes = 1;
      ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
      listen_socket = sock;
    });
  }
};

HttpApi::HttpApi(const ServerConfig& config, TokenFile& tokens, ServerCounters& counters)
    : impl_(std::make_unique<Impl>(config, tokens, counters)) {
  impl_->configure();
  impl_->install_hooks();
}

HttpApi::~HttpApi() { stop(); }

void HttpApi::route(const HandlerTable& handlers) {
  for (const protocol::Route& r : protocol::kRoutes) {
    auto it = handlers.find(r.endpoint);
    if (it == handlers.end() || !it->second)
      throw std::logic_error("server: no handler for " + std::string(to_string(r.method)) + " " +
                             protocol::full_path(r));
    impl_->add(r, it->second);
  }
}

int HttpApi::bind() {
  Impl& s = *impl_;
  int port = 0;
  if (s.config.port == 0)
    port = std::max(s.http.bind_to_any_port(s.config.host), 0);
  else
    port = s.http.bind_to_port(s.config.host, s.config.port) ? s.config.port : 0;
  if (port <= 0)
    throw std::runtime_error("server: cannot bind " + s.config.host + ":" +
                             std::to_string(s.config.port));
  // Debian's cpp-httplib is compiled with a listen backlog of 5: 50 workers
  // connecting at once overflow it and wait 1 s for a SYN retry
  // (vesper_farm_bench). listen() again on the bound socket raises it.
  if (s.listen_socket >= 0 && ::listen(s.listen_socket, SOMAXCONN) != 0)
    spdlog::warn("server: cannot raise the listen backlog: {}", std::strerror(errno));
  return port;
}

void HttpApi::serve() {
  Impl& s = *impl_;
  s.thread = std::thread([&s] { s.http.listen_after_bind(); });
  // stop() is a no-op until the accept loop runs: wait for it.
  for (int i = 0; i < 5000 && !s.http.is_running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void HttpApi::stop() {
  impl_->http.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

}  // namespace vesper
