// The server against bodies and names an attacker or an unlucky client sends
// (docs/farm.md, "Hardening"): every malformed body is a 400 with a JSON
// error that is valid UTF-8, never a 500.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>

#include "common/utf8.h"
#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// Sends raw bytes to 127.0.0.1:port and reads until the server closes the
// connection (or `seconds` pass); returns what came back and whether the
// server closed it.
std::pair<std::string, bool> exchange_raw(int port, const std::string& request, double seconds) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(uint16_t(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  timeval timeout{long(seconds), long((seconds - long(seconds)) * 1e6)};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::string answer;
  bool closed = false;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 &&
      ::send(fd, request.data(), request.size(), 0) == ssize_t(request.size())) {
    char buf[4096];
    for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, 0)) != 0;) {
      if (n < 0) break;  // timed out: still open
      answer.append(buf, size_t(n));
    }
    closed = ::recv(fd, buf, sizeof buf, MSG_DONTWAIT) == 0;
  }
  ::close(fd);
  return {answer, closed};
}

fs::perms mode_of(const fs::path& p) { return fs::status(p).permissions() & fs::perms::mask; }

class HardeningTest : public ServerTest {
 protected:
  // POST of raw bytes; returns (status, parsed error body).
  std::pair<int, json> post_raw(const std::string& path, const std::string& body,
                                const httplib::Headers& h) {
    auto r = client().Post(("/api/v1" + path).c_str(), h, body, "application/json");
    EXPECT_TRUE(r) << path;
    if (!r) return {0, {}};
    EXPECT_TRUE(is_valid_utf8(r->body)) << r->body;
    return {r->status, r->body.empty() ? json() : json::parse(r->body, nullptr, false)};
  }
};

TEST_F(HardeningTest, MalformedBodiesAre400WithAValidUtf8Error) {
  start();
  const std::string worker = register_worker("w");
  const std::string scene = put_blob("{\"format\": \"vesper-scene/1\"}");
  submit(1);
  const std::string lease_id = lease(worker).at("lease_id");
  const std::string job_head = "{\"scene\": \"" + scene + "\", \"frames\": \"1\", ";
  const std::vector<std::tuple<std::string, std::string, httplib::Headers>> cases = {
      {"/workers/register", "{\"name\": \"a\xff\"}", wrk()},
      {"/workers/register", "{\"name\": \"\xe6\xbc\"}", wrk()},
      {"/workers/register", "{\"n\xc3\x28\": 1}", wrk()},
      {"/jobs", job_head + "\"name\": \"\xc0\xaf\"}", sub()},
      {"/jobs", job_head + "\"spp\": 1e400}", sub()},
      {"/jobs", job_head + "\"spp\": -1e400}", sub()},
      {"/jobs", job_head + "\"spp\": 1e30}", sub()},
      {"/jobs", job_head + "\"noise_target\": 1e400}", sub()},
      {"/heartbeat", "{\"lease_id\": \"" + lease_id + "\", \"progress\": 1e400}", wrk()},
      {"/heartbeat", "{\"lease_id\": \"" + lease_id + "\", \"progress\": -1e400}", wrk()},
      {"/jobs", std::string(200, '[') + std::string(200, ']'), sub()},
      {"/lease", "{\"worker_id\": " + std::string(100000, '[') + "}", wrk()},
  };
  for (const auto& [path, body, headers] : cases) {
    const auto [status, error] = post_raw(path, body, headers);
    EXPECT_EQ(status, 400) << path << " " << utf8_safe(body, 200);
    EXPECT_TRUE(error.is_object() && error.contains("error")) << error.dump();
  }
  // The lease is still alive: nothing above touched it.
  const auto [status, answer] =
      post_raw("/heartbeat", "{\"lease_id\": \"" + lease_id + "\", \"progress\": 0.5}", wrk());
  EXPECT_EQ(status, 200) << answer.dump();
}

// Messages quote what was sent, cut to 80 bytes: never inside a character.
TEST_F(HardeningTest, QuotedValuesAreCutAtCharacterBoundaries) {
  start();
  for (size_t ascii = 75; ascii <= 80; ++ascii) {
    const std::string id = std::string(ascii, 'x') + "漢字漢字";
    auto [status, error] = post_raw("/heartbeat", json{{"lease_id", id}}.dump(), wrk());
    EXPECT_EQ(status, 409) << ascii;
    std::tie(status, error) = post_raw("/lease", json{{"worker_id", id}}.dump(), wrk());
    EXPECT_EQ(status, 404) << ascii;
  }
  // Path segments are bytes, not UTF-8: a frame named %FF is a 404 with a valid body.
  const int64_t job = submit(1);
  auto r = client().Get(("/api/v1/jobs/" + std::to_string(job) + "/frames/%FF%FE").c_str(), sub());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_TRUE(is_valid_utf8(r->body)) << r->body;
  r = client().Get("/api/v1/blobs/%FF%FE", sub());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_TRUE(is_valid_utf8(r->body)) << r->body;
}

// Names end up on terminals and in file names: control characters are
// refused where they enter, naming the field.
TEST_F(HardeningTest, ControlCharactersInNamesAre400NamingTheField) {
  start();
  const std::string scene = put_blob("{\"format\": \"vesper-scene/1\"}");
  const std::string asset = put_blob("v 0 0 0\n");
  for (const std::string& bad :
       {std::string("a\x1b[31mred"), std::string("two\nlines"), std::string("cr\rx"),
        std::string("nul\0x", 5), std::string("c1\xc2\x9b")}) {
    auto [status, error] = post_raw("/workers/register", json{{"name", bad}}.dump(), wrk());
    EXPECT_EQ(status, 400);
    EXPECT_EQ(error.value("path", ""), "/name") << error.dump();
    EXPECT_NE(error.value("error", "").find("control character"), std::string::npos)
        << error.dump();
    std::tie(status, error) =
        post_raw("/jobs", json{{"name", bad}, {"scene", scene}, {"frames", "1"}}.dump(), sub());
    EXPECT_EQ(status, 400);
    EXPECT_EQ(error.value("path", ""), "/name") << error.dump();
    const json assets = json::array({{{"name", "assets/" + bad}, {"blob", asset}}});
    std::tie(status, error) = post_raw(
        "/jobs", json{{"scene", scene}, {"frames", "1"}, {"assets", assets}}.dump(), sub());
    EXPECT_EQ(status, 400);
    EXPECT_EQ(error.value("path", ""), "/assets/0/name") << error.dump();
    // The message shows the name escaped, never the raw control character.
    EXPECT_EQ(error.value("error", "").find_first_of(std::string("\x1b\n\r\0", 4)),
              std::string::npos)
        << error.dump();
  }
  // Printable Unicode is a name like any other.
  EXPECT_EQ(post_raw("/workers/register", json{{"name", "rendu-été 渲染"}}.dump(), wrk()).first,
            200);
}

// A request with two Content-Length headers (or one beside Transfer-Encoding)
// is how a request is smuggled: refused at once, before any body is read, and
// the connection closed, so the smuggled request is never answered.
TEST_F(HardeningTest, AmbiguousBodyLengthsAre400AndCloseTheConnection) {
  start();
  const std::string smuggled = "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
  const std::string cl = "Content-Length: " + std::to_string(smuggled.size()) + "\r\n";
  for (const std::string& lengths :
       {cl + "Content-Length: 0\r\n", "Content-Length: 0\r\n" + cl,
        "Content-Length: 2000000000\r\n" + cl, cl + "Transfer-Encoding: chunked\r\n"}) {
    const std::string request =
        "POST /api/v1/workers/register HTTP/1.1\r\nHost: x\r\n"
        "Authorization: Bearer " +
        server_->worker_token() + "\r\n" + lengths + "\r\n" + smuggled;
    const auto [answer, closed] = exchange_raw(port_, request, 3);
    EXPECT_EQ(answer.rfind("HTTP/1.1 400", 0), 0u) << answer;
    EXPECT_NE(answer.find("Content-Length"), std::string::npos) << answer;
    EXPECT_EQ(answer.find("\r\n\r\nok"), std::string::npos) << "smuggled request answered";
    EXPECT_EQ(answer.find("HTTP/1.1 200"), std::string::npos) << answer;
    EXPECT_TRUE(closed) << lengths;
  }
  // One Content-Length is a request like any other, on a kept-alive connection.
  const std::string body = json{{"name", "ok"}}.dump();
  const auto [answer, closed] =
      exchange_raw(port_,
                   "POST /api/v1/workers/register HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " +
                       server_->worker_token() +
                       "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body,
                   0.5);
  EXPECT_EQ(answer.rfind("HTTP/1.1 200", 0), 0u) << answer;
  EXPECT_FALSE(closed);
}

// The data dir is 0700 and the store's files and blobs 0600, whatever
// existed before (a dir made by hand, files of an older server).
TEST_F(HardeningTest, DataDirAndItsFilesArePrivateWhateverExistedBefore) {
  const fs::path data = dir_ / "data";
  const fs::path old_blob = data / "blobs" / "ab" / std::string(62, 'c');
  fs::create_directories(old_blob.parent_path());
  std::ofstream(old_blob) << "old";
  std::ofstream(data / "jobs.sqlite");  // empty: SQLite makes it a database
  std::ofstream(data / "workers.json") << R"({"workers": []})";
  const auto world_readable = fs::perms::owner_read | fs::perms::owner_write |
                              fs::perms::group_read | fs::perms::others_read;
  fs::permissions(data, world_readable | fs::perms::owner_exec | fs::perms::group_exec |
                            fs::perms::others_exec);
  for (const fs::path& f : {old_blob, data / "jobs.sqlite", data / "workers.json"})
    fs::permissions(f, world_readable);
  start();
  register_worker("w");
  const std::string blob = put_blob("new bytes");
  submit(1);
  EXPECT_EQ(mode_of(data), fs::perms::owner_all);
  const auto private_file = fs::perms::owner_read | fs::perms::owner_write;
  for (const char* name :
       {"jobs.sqlite", "jobs.sqlite-wal", "jobs.sqlite-shm", "workers.json", "tokens.json"})
    EXPECT_EQ(mode_of(data / name), private_file) << name;
  EXPECT_EQ(mode_of(old_blob), private_file);
  EXPECT_EQ(mode_of(data / "blobs" / blob.substr(0, 2) / blob.substr(2)), private_file);
  // A fresh data dir is private from the start.
  ServerConfig c = config();
  c.data_dir = dir_ / "fresh";
  start(c);
  EXPECT_EQ(mode_of(c.data_dir), fs::perms::owner_all);
  EXPECT_EQ(mode_of(c.data_dir / "jobs.sqlite"), private_file);
}

// A submitted scene may not reference files outside its task directory: an
// absolute path or '..' would render the worker's own files into the frame.
TEST_F(HardeningTest, SceneReferencesOutsideTheTaskDirectoryAre400) {
  start();
  const json base = {{"format", "vesper-scene/1"},
                     {"shapes", json::array({{{"type", "mesh"}, {"file", "assets/cube.obj"}}})}};
  const std::string cube = put_blob("v 0 0 0\n");
  const json assets = json::array({{{"name", "assets/cube.obj"}, {"blob", cube}}});
  struct Case {
    std::string json_path;
    json scene;
  };
  json env = base, vdb = base, deep = base;
  env["lights"] = json::array({{{"type", "environment"}, {"file", "/etc/passwd"}}});
  vdb["media"] = {{"smoke", {{"type", "vdb"}, {"file", "../../smoke.vdb"}}}};
  deep["shapes"][0]["file"] = "assets/../../../home/x.obj";
  for (const auto& [path, scene] : {Case{"/lights/0/file", env}, Case{"/media/smoke/file", vdb},
                                    Case{"/shapes/0/file", deep}}) {
    const std::string blob = put_blob(scene.dump());
    for (const char* query : {"", "?dry_run=1"}) {
      const auto [status, error] =
          post_raw(std::string("/jobs") + query,
                   json{{"scene", blob}, {"frames", "1"}, {"assets", assets}}.dump(), sub());
      EXPECT_EQ(status, 400) << path;
      EXPECT_EQ(error.value("path", ""), "/scene") << error.dump();
      const std::string message = error.value("error", "");
      EXPECT_NE(message.find(path + ": '"), std::string::npos) << message;
      EXPECT_NE(message.find("outside its directory"), std::string::npos) << message;
    }
  }
  EXPECT_EQ(get_ok("/jobs").at("jobs").size(), 0u);
  // Inside the directory, and scenes that are not JSON (the renderer says why).
  EXPECT_EQ(
      post_raw("/jobs",
               json{{"scene", put_blob(base.dump())}, {"frames", "1"}, {"assets", assets}}.dump(),
               sub())
          .first,
      201);
  EXPECT_EQ(
      post_raw("/jobs", json{{"scene", put_blob("not json")}, {"frames", "1"}}.dump(), sub()).first,
      201);
}

// The lease carries the job's task timeout, else the server's default.
TEST_F(HardeningTest, LeasesCarryTheTaskTimeout) {
  ServerConfig c = config();
  c.task_timeout = 120;
  start(c);
  const std::string scene = put_blob("{}");
  for (const json& bad : {json(0), json(-1), json(1e9), json("60")}) {
    const auto [status, error] = post_raw(
        "/jobs", json{{"scene", scene}, {"frames", "1"}, {"task_timeout", bad}}.dump(), sub());
    EXPECT_EQ(status, 400) << bad;
    EXPECT_EQ(error.value("path", ""), "/task_timeout") << error.dump();
  }
  post_ok("/jobs", {{"scene", scene}, {"frames", "1"}, {"task_timeout", 7.5}}, sub(), 201);
  post_ok("/jobs", {{"scene", scene}, {"frames", "1"}}, sub(), 201);
  const std::string w = register_worker("w");
  EXPECT_EQ(lease(w).at("task_timeout"), 7.5);
  EXPECT_EQ(lease(w).at("task_timeout"), 120);
  c = config();
  c.task_timeout = 0;  // no farm default
  start(c);
  post_ok("/jobs", {{"scene", scene}, {"frames", "1"}}, sub(), 201);
  EXPECT_FALSE(lease(w).contains("task_timeout"));
}

}  // namespace
}  // namespace vesper
