// The connection layer against slow and oversized clients (docs/farm.md,
// "Hardening"): slow request heads cannot starve /healthz or leasing, the
// token and the size limits are decided from the head before any body byte
// is read, heads and idle keep-alive connections have deadlines, and the
// number of open connections is bounded (503 beyond).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A raw TCP connection to 127.0.0.1:port, for what httplib::Client cannot
// send (half a request head, a body that never comes).
class Raw {
 public:
  explicit Raw(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(uint16_t(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~Raw() { ::close(fd_); }
  Raw(const Raw&) = delete;
  Raw& operator=(const Raw&) = delete;

  bool connected() const { return connected_; }
  bool send(const std::string& bytes) {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == ssize_t(bytes.size());
  }
  // Reads until an answer's head (and its Content-Length of body) is in,
  // the server closes, or `seconds` pass.
  std::string answer(double seconds) {
    const auto start = Clock::now();
    std::string got;
    for (double left; (left = seconds - seconds_since(start)) > 0;) {
      const size_t head = got.find("\r\n\r\n");
      if (head != std::string::npos) {
        const size_t cl = got.find("Content-Length: ");
        const size_t length = cl < head ? std::stoul(got.substr(cl + 16)) : 0;
        if (got.size() >= head + 4 + length) break;
      }
      if (!readable(left)) break;
      char buf[4096];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) {
        closed_ = true;
        break;
      }
      got.append(buf, size_t(n));
    }
    return got;
  }
  // Whether the server closes the connection within `seconds` (data it
  // sends meanwhile is dropped).
  bool closed_within(double seconds) {
    const auto start = Clock::now();
    for (double left; !closed_ && (left = seconds - seconds_since(start)) > 0;) {
      if (!readable(left)) break;
      char buf[4096];
      if (::recv(fd_, buf, sizeof buf, 0) <= 0) closed_ = true;
    }
    return closed_;
  }

 private:
  bool readable(double seconds) {
    pollfd p{fd_, POLLIN, 0};
    return ::poll(&p, 1, int(seconds * 1000) + 1) > 0;
  }
  int fd_;
  bool connected_ = false, closed_ = false;
};

// The high-water mark of this process's resident memory, bytes.
size_t peak_rss() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stoul(line.substr(6)) * 1024;
  return 0;
}

class ConnectionTest : public ServerTest {};

// 200 clients trickling request heads (one header line every 0.5 s): the
// old server's 16 threads all waited on them, and /healthz and leasing
// stopped for as long as they kept trickling.
TEST_F(ConnectionTest, SlowHeadsDoNotStopHealthzOrLeasing) {
  start();
  const std::string worker = register_worker("w");
  submit(3);
  std::vector<std::unique_ptr<Raw>> slow;
  for (int i = 0; i < 200; ++i) {
    slow.push_back(std::make_unique<Raw>(port_));
    ASSERT_TRUE(slow.back()->connected());
    slow.back()->send("GET /healthz HTTP/1.1\r\nHost: x\r\n");
  }
  std::atomic<bool> done{false};
  std::thread trickle([&] {
    for (int round = 0; round < 16 && !done; ++round) {  // at most 8 s
      for (auto& c : slow) c->send("X-Slow: " + std::to_string(round) + "\r\n");
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto quick = [this] {
    httplib::Client c("127.0.0.1", port_);
    c.set_connection_timeout(2);
    c.set_read_timeout(2);
    return c;
  };
  int healthy = 0;
  const auto start_time = Clock::now();
  for (int i = 0; i < 10; ++i) {
    auto r = quick().Get("/healthz");
    healthy += r && r->status == 200;
  }
  auto leased =
      quick().Post("/api/v1/lease", wrk(), json{{"worker_id", worker}}.dump(), "application/json");
  const double took = seconds_since(start_time);
  done = true;
  trickle.join();
  EXPECT_EQ(healthy, 10);
  ASSERT_TRUE(leased) << "no answer to /lease under 200 slow connections";
  EXPECT_EQ(leased->status, 200) << leased->body;
  EXPECT_LT(took, 2.0);
}

// An unauthenticated request announcing a 2 GB body is refused from its head
// (401), and an authenticated one over the limit too (413): at once, without
// waiting for a body that never comes (the old server answered 413 after its
// 30 s read timeout). A POST without Content-Length is 411.
TEST_F(ConnectionTest, OversizedAndUnauthenticatedBodiesAreRefusedFromTheHead) {
  start();
  const std::string blob = "/api/v1/blobs/" + std::string(64, 'a');
  const std::string huge = "Content-Length: 2000000000\r\n\r\nhello";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"PUT " + blob + " HTTP/1.1\r\nHost: x\r\n" + huge, "HTTP/1.1 401"},
      {"PUT " + blob + " HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " + server_->worker_token() +
           "\r\n" + huge,
       "HTTP/1.1 413"},
      {"POST /api/v1/lease HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " +
           server_->worker_token() + "\r\n" + huge,
       "HTTP/1.1 413"},
      {"POST /api/v1/lease HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " +
           server_->worker_token() + "\r\n\r\n",
       "HTTP/1.1 411"},
  };
  for (const auto& [request, expected] : cases) {
    Raw c(port_);
    const auto t = Clock::now();
    ASSERT_TRUE(c.send(request));
    const std::string answer = c.answer(3);
    EXPECT_EQ(answer.rfind(expected, 0), 0u) << request.substr(0, 40) << " -> " << answer;
    EXPECT_LT(seconds_since(t), 1.0) << answer;
  }
}

// Four unauthenticated 60 MiB PUTs: 401 from the head, before the body is
// sent, and the bodies are never held in memory (the old server read each
// into memory first).
TEST_F(ConnectionTest, UnauthenticatedUploadsAreRefusedBeforeTheirBody) {
  start();
  const size_t before = peak_rss();
  const size_t body = size_t(60) << 20;
  std::vector<std::thread> clients;
  std::atomic<int> refused_first{0};
  for (int i = 0; i < 4; ++i)
    clients.emplace_back([&, i] {
      Raw c(port_);
      c.send("PUT /api/v1/blobs/" + std::string(63, 'b') + char('0' + i) +
             " HTTP/1.1\r\nHost: x\r\nContent-Length: " + std::to_string(body) + "\r\n\r\n");
      const std::string answer = c.answer(2);  // nothing of the body sent yet
      refused_first += answer.rfind("HTTP/1.1 401", 0) == 0;
      const std::string chunk(1 << 20, 'z');
      for (size_t sent = 0; sent < body && c.send(chunk); sent += chunk.size()) {
      }
    });
  for (auto& t : clients) t.join();
  EXPECT_EQ(refused_first, 4);
  EXPECT_LT(peak_rss() - before, size_t(32) << 20) << "unauthenticated bodies were read";
}

// A client that keeps trickling its head is cut off at the header deadline
// (408 and closed); the old server waited as long as each byte came within
// its 30 s read timeout.
TEST_F(ConnectionTest, HeaderDeadlineClosesATricklingConnection) {
  ServerConfig c = config();
  c.header_timeout = 1;  // new-api
  start(c);
  Raw slow(port_);
  ASSERT_TRUE(slow.send("GET /healthz HTTP/1.1\r\n"));
  const auto t = Clock::now();
  bool closed = false;
  for (int i = 0; i < 20 && !closed; ++i) {  // at most 4 s
    slow.send("X-Slow: " + std::to_string(i) + "\r\n");
    closed = slow.closed_within(0.2);
  }
  EXPECT_TRUE(closed) << "a head trickled for 4 s was not cut off";
  EXPECT_LT(seconds_since(t), 2.5);
}

// One connection over max_connections is answered 503 and closed; the
// others are still served.
TEST_F(ConnectionTest, ConnectionsOverTheCapAre503) {
  ServerConfig c = config();
  c.max_connections = 8;  // new-api
  start(c);
  std::vector<std::unique_ptr<Raw>> open;
  for (int i = 0; i < 8; ++i) {
    open.push_back(std::make_unique<Raw>(port_));
    ASSERT_TRUE(open.back()->connected());
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // all accepted
  Raw extra(port_);
  extra.send("GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n");
  const std::string answer = extra.answer(3);
  EXPECT_EQ(answer.rfind("HTTP/1.1 503", 0), 0u) << answer;
  // An open connection is served as before.
  open[0]->send("GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_EQ(open[0]->answer(3).rfind("HTTP/1.1 200", 0), 0u);
}

// A kept-alive connection with no next request is closed after idle_timeout.
TEST_F(ConnectionTest, IdleKeepAliveConnectionsAreClosed) {
  ServerConfig c = config();
  c.idle_timeout = 0.5;  // new-api
  start(c);
  Raw conn(port_);
  conn.send("GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_EQ(conn.answer(3).rfind("HTTP/1.1 200", 0), 0u);
  const auto t = Clock::now();
  EXPECT_TRUE(conn.closed_within(3));
  EXPECT_LT(seconds_since(t), 1.5);
}

}  // namespace
}  // namespace vesper
