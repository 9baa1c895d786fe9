// The operator's side of result trust (docs/farm.md, "Hardening"): `vesper
// fetch` never saves a frame that is not an EXR, and `vesper tokens` makes
// and revokes per-worker tokens that a running server honours at once.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>

#include "common/sha256.h"
#include "server/server.h"
#include "tests/common/cli_runner.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

class TrustCliTest : public CliTest {
 protected:
  TrustCliTest() : CliTest("") {}
  void TearDown() override { server_.reset(); }

  void start(bool verify) {
    ServerConfig c;
    c.data_dir = dir_ / "data";
    c.verify_results = verify;
    server_ = std::make_unique<Server>(c);
    port_ = server_->start();
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(10);
    return c;
  }
  httplib::Headers bearer(const std::string& token) const {
    return {{"Authorization", "Bearer " + token}};
  }
  int post(const std::string& path, const json& body, const std::string& token,
           json* out = nullptr) {
    auto r =
        client().Post(("/api/v1" + path).c_str(), bearer(token), body.dump(), "application/json");
    if (!r) return 0;
    if (out && !r->body.empty()) *out = json::parse(r->body);
    return r->status;
  }
  std::string put(const std::string& bytes) {
    const std::string sha = sha256_hex(bytes);
    client().Put(("/api/v1/blobs/" + sha).c_str(), bearer(server_->worker_token()), bytes,
                 "application/octet-stream");
    return sha;
  }

  std::unique_ptr<Server> server_;
  int port_ = 0;
};

// A server that took junk (verify_results off: as an older server did)
// serves it as frame 1; fetch refuses it, exits non-zero and writes nothing.
TEST_F(TrustCliTest, FetchNeverSavesANonExr) {
  start(/*verify=*/false);
  const std::string w = server_->worker_token(), s = server_->submitter_token();
  json job, reg, lease;
  ASSERT_EQ(post("/jobs",
                 {{"name", "junk"},
                  {"scene", put("{\"format\": \"vesper-scene/1\"}")},
                  {"frames", "1"},
                  {"spp", 1}},
                 s, &job),
            201);
  ASSERT_EQ(post("/workers/register", {{"name", "liar"}}, w, &reg), 200);
  ASSERT_EQ(post("/lease", {{"worker_id", reg.at("worker_id")}}, w, &lease), 200);
  ASSERT_EQ(
      post("/complete", {{"lease_id", lease.at("lease_id")}, {"result", put("junk bytes")}}, w),
      200);
  const fs::path out = dir_ / "frames";
  const RunResult f = run(fmt::format("fetch {} -o {} --server http://127.0.0.1:{} --token {}",
                                      job.at("id").get<int64_t>(), out.string(), port_, s));
  EXPECT_NE(f.exit_code, 0) << f.err;
  EXPECT_NE(f.err.find("not an OpenEXR image"), std::string::npos) << f.err;
  EXPECT_TRUE(fs::is_empty(out)) << "nothing may be written";
}

// add-worker prints a token the running server takes; revoke makes it a 401
// at the next request, without a restart; list shows no secrets.
TEST_F(TrustCliTest, TokensCommandRevokesWithoutARestart) {
  start(/*verify=*/true);
  const std::string data = (dir_ / "data").string();
  const RunResult add = run("tokens --data-dir " + data + " add-worker box-1");
  ASSERT_EQ(add.exit_code, 0) << add.err;
  const std::string token = add.out.substr(0, add.out.find('\n'));
  ASSERT_EQ(token.size(), 64u) << add.out;
  EXPECT_EQ(post("/workers/register", {{"name", "box-1"}}, token), 200);
  EXPECT_NE(run("tokens --data-dir " + data + " add-worker box-1").exit_code, 0)
      << "an enabled token is not replaced silently";

  ASSERT_EQ(run("tokens --data-dir " + data + " revoke box-1").exit_code, 0);
  EXPECT_EQ(post("/workers/register", {{"name", "box-1"}}, token), 401);
  EXPECT_EQ(post("/workers/register", {{"name", "w"}}, server_->worker_token()), 200);
  ASSERT_EQ(run("tokens --data-dir " + data + " disable-shared").exit_code, 0);
  EXPECT_EQ(post("/workers/register", {{"name", "w"}}, server_->worker_token()), 401);

  const RunResult list = run("tokens --data-dir " + data + " list");
  EXPECT_EQ(list.exit_code, 0);
  EXPECT_EQ(list.out, "shared worker token: disabled\nworker box-1: revoked\n");
  EXPECT_NE(run("tokens --data-dir " + data + " revoke nobody").exit_code, 0);
}

}  // namespace
}  // namespace vesper::test
