#include "server/http_connections.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/sendfile.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <nlohmann/json.hpp>
#include <semaphore>
#include <set>
#include <stdexcept>
#include <thread>

#include "common/utf8.h"
#include "protocol/error_body.h"

namespace vesper {
namespace {

using Clock = std::chrono::steady_clock;

std::chrono::microseconds span(double seconds) {
  return std::chrono::microseconds(int64_t(seconds * 1e6));
}
Clock::time_point after(double seconds) { return Clock::now() + span(seconds); }

// Waits until `fd` is ready for `events` or `deadline` passes (false).
bool wait_for(int fd, short events, Clock::time_point deadline) {
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, events, 0};
    const int r = ::poll(&p, 1, int(std::min<int64_t>(left, INT_MAX)));
    if (r > 0) return true;  // readiness, or an error the next call reports
    if (r < 0 && errno != EINTR) return false;
  }
}

enum class Read { Data, Closed, Timeout };

// Appends what is there (at most `max` bytes) to `out`, waiting for it until
// `deadline`. The socket is non-blocking: the common case is one recv.
Read read_some(int fd, std::string& out, size_t max, Clock::time_point deadline) {
  for (;;) {
    const size_t old = out.size();
    out.resize(old + max);
    const ssize_t n = ::recv(fd, out.data() + old, max, 0);
    out.resize(old + size_t(std::max<ssize_t>(n, 0)));
    if (n > 0) return Read::Data;
    if (n == 0) return Read::Closed;
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) return Read::Closed;
    if (!wait_for(fd, POLLIN, deadline)) return Read::Timeout;
  }
}

bool write_all(int fd, const char* p, size_t n, double io_timeout) {
  while (n > 0) {
    const ssize_t w = ::send(fd, p, n, MSG_NOSIGNAL);
    if (w > 0) {
      p += w;
      n -= size_t(w);
    } else if (w < 0 && errno == EINTR) {
      continue;
    } else if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      if (!wait_for(fd, POLLOUT, after(io_timeout))) return false;
    } else {
      return false;
    }
  }
  return true;
}

bool send_file(int fd, const ApiResponse::File& file, double io_timeout) {
  const int in = ::open(file.path.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) return false;
  off_t offset = 0;
  bool ok = true;
  while (ok && uintmax_t(offset) < file.size) {
    const ssize_t n = ::sendfile(fd, in, &offset, size_t(file.size - uintmax_t(offset)));
    if (n > 0) continue;
    if (n < 0 && errno == EINTR) continue;
    ok = n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) &&
         wait_for(fd, POLLOUT, after(io_timeout));
  }
  ::close(in);
  return ok;
}

// After an answer given with the request's body unread: stop sending, then
// read and drop what the client still sends for a bounded time, so that it
// reads the answer instead of a connection reset.
void linger(int fd, double seconds) {
  ::shutdown(fd, SHUT_WR);
  const auto deadline = after(seconds);
  std::string sink;
  for (;;) {
    sink.clear();
    if (read_some(fd, sink, 64 << 10, deadline) != Read::Data) return;
  }
}

}  // namespace

ApiResponse error_response(int status, const std::string& message) {
  ApiResponse r;
  r.status = status;
  r.body = nlohmann::json(protocol::ErrorBody{utf8_safe(message), {}}).dump() + "\n";
  r.content_type = "application/json";
  return r;
}

struct HttpConnections::Impl {
  ConnectionLimits limits;
  Admit admit;
  Observe observe;
  std::counting_semaphore<> slots;
  int listen_fd = -1;
  std::thread acceptor;
  std::atomic<bool> stopping{false};

  struct Pending {
    int fd;
    Clock::time_point accepted;
  };
  std::mutex mutex;  // guards everything below
  std::condition_variable work, done;
  std::deque<Pending> pending;  // accepted, not yet taken by a thread
  std::set<int> open;           // every accepted connection not yet closed
  int live_threads = 0, idle_threads = 0;

  Impl(ConnectionLimits l, Admit a, Observe o)
      : limits(l),
        admit(std::move(a)),
        observe(std::move(o)),
        slots(std::max(1, l.handler_slots)) {}

  bool respond(int fd, const ApiResponse& r, bool head_only, bool close) {
    observe(r.status);
    std::vector<std::pair<std::string, std::string>> fields;
    if (!r.content_type.empty()) fields.emplace_back("Content-Type", r.content_type);
    const uintmax_t length = r.file ? r.file->size : r.body.size();
    if (r.status != 204 && r.status >= 200)
      fields.emplace_back("Content-Length", std::to_string(length));
    for (const auto& h : r.headers) fields.push_back(h);
    if (close) fields.emplace_back("Connection", "close");
    std::string out = response_head(r.status, fields);
    const bool body = !head_only && r.status != 204;
    // Small bodies go out with the head in one send (one segment, no Nagle wait).
    if (body && !r.file) out += r.body;
    if (!write_all(fd, out.data(), out.size(), limits.io_timeout)) return false;
    return !(body && r.file) || send_file(fd, *r.file, limits.io_timeout);
  }

  // Answers without reading the request's body; the connection closes.
  void refuse(int fd, int status, const std::string& message) {
    respond(fd, error_response(status, message), false, true);
    linger(fd, limits.linger_seconds);
  }

  // One connection, request after request, until it closes, times out, asks
  // to close or the server stops.
  void serve_connection(int fd, Clock::time_point accepted) {
    std::string buf;  // bytes read past the previous request
    bool first = true;
    while (!stopping) {
      // The next request's head: a new connection has header_timeout from
      // accept; a kept-alive one idle_timeout for its first byte, then
      // header_timeout for the rest.
      auto deadline = first ? accepted + span(limits.header_timeout) : after(limits.idle_timeout);
      if (buf.empty() && read_some(fd, buf, 16 << 10, deadline) != Read::Data) return;
      if (!first) deadline = after(limits.header_timeout);
      size_t end;
      while ((end = buf.find("\r\n\r\n")) == std::string::npos &&
             buf.size() < limits.max_header_bytes) {
        const Read r = read_some(fd, buf, 16 << 10, deadline);
        if (r == Read::Closed) return;
        if (r == Read::Timeout)
          return refuse(fd, 408,
                        "request head not complete within " +
                            std::to_string(int(limits.header_timeout)) + " s");
      }
      if (end == std::string::npos || end + 4 > limits.max_header_bytes)
        return refuse(fd, 431,
                      "request head exceeds " + std::to_string(limits.max_header_bytes) + " bytes");
      ParsedHead parsed = parse_request_head(std::string_view(buf).substr(0, end));
      buf.erase(0, end + 4);
      first = false;
      if (!parsed.head) return refuse(fd, 400, parsed.error);
      const RequestHead& h = *parsed.head;
      if (h.chunked)
        return refuse(fd, 411,
                      "a request body needs a Content-Length header (chunked transfer coding is "
                      "not accepted)");
      const bool head_only = h.method == "HEAD";
      Admission a = admit(h);
      if (a.refusal) {
        const bool body_unread = h.content_length > 0;
        if (!respond(fd, *a.refusal, head_only, body_unread || h.wants_close())) return;
        if (body_unread) linger(fd, limits.linger_seconds);
        if (body_unread || h.wants_close()) return;
        continue;
      }
      ApiResponse res;
      {
        slots.acquire();
        struct Release {
          std::counting_semaphore<>& s;
          ~Release() { s.release(); }
        } release{slots};
        std::string body;
        if (h.content_length > 0 && !read_body(fd, h, buf, body)) return;
        res = a.handle(body);
      }
      const bool close = h.wants_close() || stopping;
      if (!respond(fd, res, head_only, close) || close) return;
    }
  }

  // The body: bytes already read past the head first, then the socket.
  bool read_body(int fd, const RequestHead& h, std::string& buf, std::string& body) {
    const size_t length = size_t(h.content_length);
    if (buf.size() < length && h.field("Expect") == "100-continue") {
      static constexpr std::string_view kContinue = "HTTP/1.1 100 Continue\r\n\r\n";
      if (!write_all(fd, kContinue.data(), kContinue.size(), limits.io_timeout)) return false;
    }
    const size_t from_buf = std::min(length, buf.size());
    body.reserve(length);
    body.assign(buf, 0, from_buf);
    buf.erase(0, from_buf);
    while (body.size() < length)
      if (read_some(fd, body, length - body.size(), after(limits.io_timeout)) != Read::Data)
        return false;
    return true;
  }

  void connection_thread() {
    std::unique_lock lock(mutex);
    for (;;) {
      ++idle_threads;
      const bool woken = work.wait_for(lock, std::chrono::seconds(30),
                                       [&] { return stopping || !pending.empty(); });
      --idle_threads;
      if (stopping) break;
      // Threads beyond the handler slots' number end after 30 s without work.
      if (!woken && live_threads > limits.handler_slots) break;
      if (pending.empty()) continue;
      const Pending p = pending.front();
      pending.pop_front();
      lock.unlock();
      serve_connection(p.fd, p.accepted);
      lock.lock();
      open.erase(p.fd);
      ::close(p.fd);
    }
    if (--live_threads == 0) done.notify_all();
  }

  // A connection over the limit: a 503 written without blocking, then closed
  // once the client had a moment to read it (refused_until).
  void turn_away(int fd, std::deque<std::pair<int, Clock::time_point>>& refused) {
    const ApiResponse r = error_response(
        503, "server busy: " + std::to_string(limits.max_connections) + " connections open");
    observe(503);
    const std::string out = response_head(503, {{"Content-Type", r.content_type},
                                                {"Content-Length", std::to_string(r.body.size())},
                                                {"Connection", "close"}}) +
                            r.body;
    [[maybe_unused]] const ssize_t n = ::send(fd, out.data(), out.size(), MSG_NOSIGNAL);
    ::shutdown(fd, SHUT_WR);
    if (refused.size() >= 256) {
      ::close(refused.front().first);
      refused.pop_front();
    }
    refused.emplace_back(fd, after(0.5));
  }

  void accept_loop() {
    std::deque<std::pair<int, Clock::time_point>> refused;
    while (!stopping) {
      pollfd p{listen_fd, POLLIN, 0};
      ::poll(&p, 1, 100);
      // Turned-away connections: what they sent is dropped, then closed.
      char sink[4096];
      while (!refused.empty() && refused.front().second <= Clock::now()) {
        while (::recv(refused.front().first, sink, sizeof sink, MSG_DONTWAIT) > 0) {
        }
        ::close(refused.front().first);
        refused.pop_front();
      }
      for (;;) {
        const int fd = ::accept4(listen_fd, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
        if (fd < 0) break;  // EAGAIN; or out of descriptors: retried at the next poll
        int yes = 1;
        // Without it a response's body waits for the client's delayed ACK
        // (~40 ms per keep-alive request, vesper_farm_bench).
        ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
        std::unique_lock lock(mutex);
        if (int(open.size()) >= limits.max_connections) {
          lock.unlock();
          turn_away(fd, refused);
          continue;
        }
        open.insert(fd);
        pending.push_back({fd, Clock::now()});
        if (size_t(idle_threads) >= pending.size()) {
          work.notify_one();
        } else {
          ++live_threads;
          try {
            std::thread([this] { connection_thread(); }).detach();
          } catch (const std::system_error& e) {
            --live_threads;  // the connection waits for a thread to be free
            spdlog::warn("server: cannot start a connection thread: {}", e.what());
          }
        }
      }
    }
    for (const auto& [fd, when] : refused) ::close(fd);
  }
};

HttpConnections::HttpConnections(ConnectionLimits limits, Admit admit, Observe observe)
    : impl_(std::make_unique<Impl>(limits, std::move(admit), std::move(observe))) {}

HttpConnections::~HttpConnections() { stop(); }

int HttpConnections::bind(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE;
  addrinfo* found = nullptr;
  const std::string service = std::to_string(port);
  if (const int e = ::getaddrinfo(host.c_str(), service.c_str(), &hints, &found); e != 0)
    throw std::runtime_error("server: cannot bind " + host + ":" + service + ": " +
                             ::gai_strerror(e));
  std::string error = "no address";
  for (addrinfo* a = found; a && impl_->listen_fd < 0; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) continue;
    int yes = 1;
    // SO_REUSEADDR alone: a restart may bind over TIME_WAIT connections, but
    // a second server cannot bind the port (SO_REUSEPORT would let it take
    // half the requests).
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    if (::bind(fd, a->ai_addr, a->ai_addrlen) == 0 && ::listen(fd, SOMAXCONN) == 0) {
      impl_->listen_fd = fd;
    } else {
      error = std::strerror(errno);
      ::close(fd);
    }
  }
  ::freeaddrinfo(found);
  if (impl_->listen_fd < 0)
    throw std::runtime_error("server: cannot bind " + host + ":" + service + ": " + error);
  sockaddr_storage addr{};
  socklen_t len = sizeof addr;
  ::getsockname(impl_->listen_fd, reinterpret_cast<sockaddr*>(&addr), &len);
  return ntohs(addr.ss_family == AF_INET6 ? reinterpret_cast<sockaddr_in6&>(addr).sin6_port
                                          : reinterpret_cast<sockaddr_in&>(addr).sin_port);
}

void HttpConnections::serve() {
  if (impl_->listen_fd < 0) throw std::logic_error("HttpConnections::serve before bind");
  impl_->acceptor = std::thread([this] { impl_->accept_loop(); });
}

void HttpConnections::stop() {
  Impl& s = *impl_;
  if (s.stopping.exchange(true)) return;
  if (s.acceptor.joinable()) s.acceptor.join();
  std::unique_lock lock(s.mutex);
  for (const Impl::Pending& p : s.pending) {
    s.open.erase(p.fd);
    ::close(p.fd);
  }
  s.pending.clear();
  // Wakes every connection blocked in poll; their threads close them.
  for (int fd : s.open) ::shutdown(fd, SHUT_RDWR);
  s.work.notify_all();
  s.done.wait(lock, [&] { return s.live_threads == 0; });
  if (s.listen_fd >= 0) ::close(s.listen_fd);
  s.listen_fd = -1;
}

}  // namespace vesper
