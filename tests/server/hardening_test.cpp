// The server against bodies and names an attacker or an unlucky client sends
// (docs/farm.md, "Hardening"): every malformed body is a 400 with a JSON
// error that is valid UTF-8, never a 500.
#include <gtest/gtest.h>

#include "common/utf8.h"
#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

using json = nlohmann::json;

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
  for (const std::string& bad : {std::string("a\x1b[31mred"), std::string("two\nlines"),
                                 std::string("cr\rx"), std::string("nul\0x", 5),
                                 std::string("c1\xc2\x9b")}) {
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
    std::tie(status, error) =
        post_raw("/jobs", json{{"scene", scene}, {"frames", "1"}, {"assets", assets}}.dump(), sub());
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

}  // namespace
}  // namespace vesper
