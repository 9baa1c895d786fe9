#pragma once
// The server's connection layer (plain POSIX sockets): accepts connections,
// reads each request's head under a deadline, lets the application admit or
// refuse the request from its head alone — before a byte of its body is read
// — and runs admitted requests with at most `handler_slots` at once.
//
// Why not cpp-httplib's server (0.11.4, Debian): a connection holds one of
// its pool threads from accept to close, heads are read with a per-recv
// timeout only (a client trickling a byte every few seconds holds a thread
// forever), its queue of accepted connections is unbounded, and bodies are
// read (or drained, up to the announced length) before the handler runs.
// Here a connection has a thread of its own while it is open (cheap: it
// sleeps in poll), reused for later connections; the expensive part —
// reading the body and running the handler — is what is bounded.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "server/http_exchange.h"
#include "server/http_wire.h"

namespace vesper {

struct ConnectionLimits {
  // Open connections; one beyond is answered 503 and closed.
  int max_connections = 1024;
  // Requests whose body is read and whose handler runs at once; the others
  // wait (their connection stays open) for a slot.
  int handler_slots = 16;
  // Seconds for a whole request head: from accept for a connection's first
  // request, from the first byte for the next ones. 408 and closed beyond.
  double header_timeout = 10;
  std::size_t max_header_bytes = std::size_t(64) << 10;  // 431 and closed beyond
  // Seconds a kept-alive connection may wait for its next request.
  double idle_timeout = 5;
  // Seconds a body read or a response write may go without progress.
  double io_timeout = 30;
  // After an answer given without reading the body, how long the unread
  // bytes are drained before the connection is closed (so the client, still
  // sending, reads the answer rather than a reset).
  double linger_seconds = 2;
};

// The application's decision from a request head alone.
struct Admission {
  // Set: answered at once, the body never read (and the connection closed
  // if one was announced).
  std::optional<ApiResponse> refusal;
  // Otherwise: runs, in a handler slot, with the whole body.
  std::function<ApiResponse(const std::string& body)> handle;
};

class HttpConnections {
 public:
  using Admit = std::function<Admission(const RequestHead&)>;
  // Sees the status of every answer, just before it is written.
  using Observe = std::function<void(int status)>;

  HttpConnections(ConnectionLimits limits, Admit admit, Observe observe);
  ~HttpConnections();  // stops
  HttpConnections(const HttpConnections&) = delete;
  HttpConnections& operator=(const HttpConnections&) = delete;

  // Binds host:port (0: ephemeral) with SO_REUSEADDR (not SO_REUSEPORT: a
  // second server must not share the port) and a SOMAXCONN backlog; returns
  // the port. Throws if it cannot.
  int bind(const std::string& host, int port);
  // Accepts on a background thread.
  void serve();
  // Stops accepting, wakes every connection, waits for their threads
  // (requests being handled finish first); idempotent.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// `{"error": message}` with `status`: the connection layer's own answers
// and the application's refusals.
ApiResponse error_response(int status, const std::string& message);

}  // namespace vesper
