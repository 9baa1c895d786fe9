// The farm server over real HTTP on 127.0.0.1 (ephemeral ports), with
// httplib::Client as the client: tokens, blobs, job validation, the worker
// protocol with fencing, cancel, restart on the same data dir, metrics and
// size limits.
#include <gtest/gtest.h>
#include <httplib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <thread>

#include "server/server.h"
#include "server/sha256.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vesper-server-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    clock_ = std::make_shared<std::atomic<double>>(1000.0);
  }
  void TearDown() override {
    server_.reset();
    fs::remove_all(dir_);
  }

  ServerConfig config() const {
    ServerConfig c;
    c.data_dir = dir_ / "data";
    c.lease_seconds = 10;
    auto clock = clock_;
    c.clock = [clock] { return clock->load(); };
    return c;
  }
  // (Re)starts the server on the same data dir.
  void start(ServerConfig c) {
    server_.reset();
    server_ = std::make_unique<Server>(std::move(c));
    port_ = server_->start();
    ASSERT_GT(port_, 0);
  }
  void start() { start(config()); }
  void advance(double seconds) { clock_->store(clock_->load() + seconds); }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(10);
    return c;
  }
  static httplib::Headers auth(const std::string& token) {
    return {{"Authorization", "Bearer " + token}};
  }
  httplib::Headers sub() const { return auth(server_->submitter_token()); }
  httplib::Headers wrk() const { return auth(server_->worker_token()); }

  httplib::Result post(const std::string& path, const json& body, const httplib::Headers& h) {
    return client().Post(("/api/v1" + path).c_str(), h, body.dump(), "application/json");
  }
  json post_ok(const std::string& path, const json& body, const httplib::Headers& h,
               int status = 200) {
    auto r = post(path, body, h);
    EXPECT_TRUE(r) << path;
    if (!r) return {};
    EXPECT_EQ(r->status, status) << path << ": " << r->body;
    return r->body.empty() ? json() : json::parse(r->body);
  }
  json get_ok(const std::string& path) {
    auto r = client().Get(("/api/v1" + path).c_str(), sub());
    EXPECT_TRUE(r);
    if (!r) return {};
    EXPECT_EQ(r->status, 200) << path << ": " << r->body;
    return json::parse(r->body);
  }
  // Uploads bytes as a blob; returns the hash.
  std::string put_blob(const std::string& bytes) {
    const std::string h = sha256_hex(bytes);
    auto r = client().Put(("/api/v1/blobs/" + h).c_str(), wrk(), bytes, "application/octet-stream");
    EXPECT_TRUE(r);
    if (r) {
      EXPECT_TRUE(r->status == 201 || r->status == 200) << r->body;
    }
    return h;
  }
  int64_t submit(int frames, int spp = 8, int split = 0, int max_attempts = 3) {
    const std::string scene = put_blob("{\"format\": \"vesper-scene/1\"}");
    json body{{"name", "test"},
              {"scene", scene},
              {"frames", "1-" + std::to_string(frames)},
              {"spp", spp},
              {"max_attempts", max_attempts}};
    if (split) body["samples_per_task"] = split;
    return post_ok("/jobs", body, sub(), 201).at("id").get<int64_t>();
  }
  std::string register_worker(const std::string& name) {
    return post_ok("/workers/register", {{"name", name}}, wrk()).at("worker_id");
  }
  json lease(const std::string& worker) {
    return post_ok("/lease", {{"worker_id", worker}}, wrk());
  }

  fs::path dir_;
  std::shared_ptr<std::atomic<double>> clock_;
  std::unique_ptr<Server> server_;
  int port_ = 0;
};

TEST_F(ServerTest, TokenFileIsPrivateAndReusedOnRestart) {
  start();
  const fs::path file = dir_ / "data" / "tokens.json";
  struct stat st {};
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  const std::string s = server_->submitter_token(), w = server_->worker_token();
  EXPECT_TRUE(is_sha256_hex(s));  // 32 random bytes as hex
  EXPECT_NE(s, w);
  std::ifstream in(file);
  const json j = json::parse(in);
  EXPECT_EQ(j.at("submitter"), s);
  EXPECT_EQ(j.at("worker"), w);

  start();  // same data dir
  EXPECT_EQ(server_->submitter_token(), s);
  EXPECT_EQ(server_->worker_token(), w);

  // A token file others can read is refused.
  server_.reset();
  fs::permissions(file, fs::perms::others_read, fs::perm_options::add);
  EXPECT_THROW(Server{config()}, std::runtime_error);
}

TEST_F(ServerTest, MissingOrWrongTokenIs401) {
  start();
  auto c = client();
  auto r = c.Get("/api/v1/jobs");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  EXPECT_TRUE(json::parse(r->body).contains("error"));
  r = c.Get("/api/v1/jobs", auth(std::string(64, 'a')));
  EXPECT_EQ(r->status, 401);
  r = c.Get("/api/v1/jobs", {{"Authorization", server_->submitter_token()}});  // no "Bearer "
  EXPECT_EQ(r->status, 401);
  r = c.Get("/api/v1/jobs", wrk());  // a worker cannot list or submit jobs
  EXPECT_EQ(r->status, 401);
  r = c.Get("/api/v1/jobs", sub());
  EXPECT_EQ(r->status, 200);
  // ... and a submitter cannot lease.
  EXPECT_EQ(post("/workers/register", {{"name", "w"}}, sub())->status, 401);
  EXPECT_EQ(post("/lease", {{"worker_id", "x"}}, {})->status, 401);
  EXPECT_EQ(c.Put("/api/v1/blobs/" + sha256_hex("x"), "x", "application/octet-stream")->status,
            401);
  // /healthz needs no token, /metrics needs one of the two.
  r = c.Get("/healthz");
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, "ok\n");
  EXPECT_EQ(c.Get("/metrics")->status, 401);
  EXPECT_EQ(c.Get("/metrics", wrk())->status, 200);
  EXPECT_EQ(c.Get("/metrics", sub())->status, 200);
}

TEST_F(ServerTest, BlobsAreVerifiedAndContentAddressed) {
  start();
  auto c = client();
  const std::string bytes = "scene bytes\n";
  const std::string good = sha256_hex(bytes);
  const std::string other = sha256_hex("something else");
  // Content that does not match its name is rejected and not stored.
  auto r = c.Put(("/api/v1/blobs/" + other).c_str(), wrk(), bytes, "application/octet-stream");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 422) << r->body;
  EXPECT_NE(json::parse(r->body).at("error").get<std::string>().find(good), std::string::npos);
  EXPECT_EQ(c.Head(("/api/v1/blobs/" + other).c_str(), wrk())->status, 404);

  EXPECT_EQ(c.Head(("/api/v1/blobs/" + good).c_str(), wrk())->status, 404);
  r = c.Put(("/api/v1/blobs/" + good).c_str(), sub(), bytes, "application/octet-stream");
  EXPECT_EQ(r->status, 201) << r->body;
  r = c.Put(("/api/v1/blobs/" + good).c_str(), wrk(), bytes, "application/octet-stream");
  EXPECT_EQ(r->status, 200);  // idempotent
  r = c.Head(("/api/v1/blobs/" + good).c_str(), wrk());
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->get_header_value("Content-Length"), std::to_string(bytes.size()));
  EXPECT_TRUE(r->body.empty());
  r = c.Get(("/api/v1/blobs/" + good).c_str(), sub());
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, bytes);
  EXPECT_TRUE(fs::exists(dir_ / "data" / "blobs" / good.substr(0, 2) / good.substr(2)));
  EXPECT_EQ(c.Get(("/api/v1/blobs/" + good).c_str())->status, 401);
}

TEST_F(ServerTest, BlobNamesCannotEscapeTheStore) {
  start();
  auto c = client();
  const std::string bytes = "x";
  std::string upper = sha256_hex(bytes);
  for (char& ch : upper) ch = char(std::toupper(ch));
  for (const std::string& name :
       {std::string("..%2F..%2Ftokens.json"), std::string("..%2f..%2f") + sha256_hex(bytes),
        std::string("%2E%2E"), std::string("abc"), upper, sha256_hex(bytes) + "0",
        sha256_hex(bytes).substr(0, 62) + "%2F.", std::string("%2Fetc%2Fpasswd"),
        std::string("zz") + sha256_hex(bytes).substr(2)}) {
    auto r = c.Put(("/api/v1/blobs/" + name).c_str(), wrk(), bytes, "application/octet-stream");
    ASSERT_TRUE(r) << name;
    EXPECT_EQ(r->status, 400) << name << ": " << r->body;
    r = c.Head(("/api/v1/blobs/" + name).c_str(), wrk());
    EXPECT_EQ(r->status, 400) << name;
  }
  // Literal dots in the path too (the client sends them as they are).
  auto r = c.Get("/api/v1/blobs/../tokens.json", wrk());
  ASSERT_TRUE(r);
  EXPECT_NE(r->status, 200);
  EXPECT_EQ(r->body.find(server_->submitter_token()), std::string::npos);
  // Nothing was written outside blobs/ab/...
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "data" / "blobs"))
    EXPECT_FALSE(e.is_regular_file()) << e.path();
}

TEST_F(ServerTest, MalformedJobIs400NamingTheJsonPath) {
  start();
  const std::string scene = put_blob("scene");
  const json good{{"name", "n"}, {"scene", scene}, {"frames", "1-10x2"}, {"spp", 16}};
  struct Case {
    json patch;
    std::string path;
  };
  const std::vector<Case> cases = {
      {{{"frames", "5-1"}}, "/frames"},
      {{{"frames", ""}}, "/frames"},
      {{{"frames", 7}}, "/frames"},
      {{{"frames", json::array({1, "two"})}}, "/frames/1"},
      {{{"spp", "ten"}}, "/spp"},
      {{{"spp", 0}}, "/spp"},
      {{{"spp", 1.5}}, "/spp"},
      {{{"samples_per_task", -1}}, "/samples_per_task"},
      {{{"max_attempts", 0}}, "/max_attempts"},
      {{{"priority", "high"}}, "/priority"},
      {{{"name", 3}}, "/name"},
      {{{"colour", "red"}}, "/colour"},  // unknown keys are rejected
      {{{"scene", "scene.json"}}, "/scene"},
      {{{"scene", sha256_hex("never uploaded")}}, "/scene"},
      {{{"frames", "1-100000"}, {"spp", 64}, {"samples_per_task", 1}}, "/samples_per_task"},
  };
  for (const Case& k : cases) {
    json body = good;
    body.update(k.patch);
    auto r = post("/jobs", body, sub());
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << k.patch.dump() << ": " << r->body;
    const json e = json::parse(r->body);
    EXPECT_EQ(e.value("path", ""), k.path) << r->body;
    EXPECT_FALSE(e.value("error", "").empty());
  }
  json missing = good;
  missing.erase("frames");
  auto r = post("/jobs", missing, sub());
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(json::parse(r->body).at("path"), "/frames");
  EXPECT_NE(json::parse(r->body).at("error").get<std::string>().find("missing"), std::string::npos);
  r = client().Post("/api/v1/jobs", sub(), "{not json", "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(post("/jobs", json::array(), sub())->status, 400);
  // Nothing was created by any of them.
  EXPECT_TRUE(get_ok("/jobs").at("jobs").empty());
  // The good one is accepted.
  EXPECT_EQ(post("/jobs", good, sub())->status, 201);
}

TEST_F(ServerTest, DryRunValidatesAndCreatesNothing) {
  start();
  const std::string scene = put_blob("scene");
  const json body{{"scene", scene}, {"frames", "1-10x2"}, {"spp", 10}, {"samples_per_task", 4}};
  auto r = client().Post("/api/v1/jobs?dry_run=1", sub(), body.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  const json j = json::parse(r->body);
  EXPECT_EQ(j.at("dry_run"), true);
  EXPECT_EQ(j.at("frame_count"), 5);
  EXPECT_EQ(j.at("task_count"), 15);  // 5 frames x ceil(10 / 4)
  EXPECT_TRUE(get_ok("/jobs").at("jobs").empty());
  // A dry run of a bad job fails like the real thing.
  json bad = body;
  bad["frames"] = "x";
  r = client().Post("/api/v1/jobs?dry_run=1", sub(), bad.dump(), "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(json::parse(r->body).at("path"), "/frames");
}

TEST_F(ServerTest, FullWorkerProtocol) {
  start();
  const int64_t job = submit(2, 8, 4);  // 2 frames x 2 sample ranges
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(job)).at("tasks").size(), 4u);
  const std::string w = register_worker("box-1");

  std::vector<std::string> results;
  for (int i = 0; i < 4; ++i) {
    const json l = lease(w);
    ASSERT_TRUE(l.contains("lease_id")) << l.dump();
    EXPECT_EQ(l.at("expiry").get<double>(), clock_->load() + 10);
    EXPECT_EQ(l.at("spp"), 8);
    EXPECT_TRUE(is_sha256_hex(l.at("scene").get<std::string>()));
    const json task = l.at("task");
    EXPECT_EQ(task.at("job_id"), job);
    EXPECT_EQ(task.at("sample_end").get<int>() - task.at("sample_begin").get<int>(), 4);
    // The scene is downloadable with the worker token.
    auto r = client().Get(("/api/v1/blobs/" + l.at("scene").get<std::string>()).c_str(), wrk());
    EXPECT_EQ(r->status, 200);

    advance(3);
    json hb = post_ok("/heartbeat", {{"lease_id", l.at("lease_id")}, {"progress", 0.5}}, wrk());
    EXPECT_EQ(hb.at("answer"), "keep_running");
    if (i == 0) {
      const json j = get_ok("/jobs/" + std::to_string(job));
      EXPECT_EQ(j.at("counts").at("leased"), 1);
      bool seen = false;
      for (const auto& t : j.at("tasks"))
        if (t.at("state") == "leased") {
          EXPECT_EQ(t.at("progress"), 0.5);
          EXPECT_EQ(t.at("worker"), w);
          seen = true;
        }
      EXPECT_TRUE(seen);
      // Progress outside [0, 1] is a 400 at /progress.
      auto bad = post("/heartbeat", {{"lease_id", l.at("lease_id")}, {"progress", 2}}, wrk());
      EXPECT_EQ(bad->status, 400);
      EXPECT_EQ(json::parse(bad->body).at("path"), "/progress");
      // Completing with a result that was never uploaded is refused.
      bad = post("/complete", {{"lease_id", l.at("lease_id")}, {"result", sha256_hex("nope")}},
                 wrk());
      EXPECT_EQ(bad->status, 400);
      EXPECT_EQ(json::parse(bad->body).at("path"), "/result");
    }
    const std::string result = put_blob("exr of task " + task.at("id").dump());
    results.push_back(result);
    post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", result}}, wrk());
  }
  // Nothing left: 204 with no body.
  auto r = post("/lease", {{"worker_id", w}}, wrk());
  EXPECT_EQ(r->status, 204);
  EXPECT_TRUE(r->body.empty());

  const json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("counts").at("done"), 4);
  EXPECT_EQ(j.at("finished"), true);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(j.at("tasks")[i].at("result"), results[i]);
  const json jobs = get_ok("/jobs").at("jobs");
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].at("state"), "active");

  // Workers list with last-seen times.
  const json workers = get_ok("/workers").at("workers");
  ASSERT_EQ(workers.size(), 1u);
  EXPECT_EQ(workers[0].at("name"), "box-1");
  EXPECT_EQ(workers[0].at("last_seen").get<double>(), clock_->load());
  // An unknown worker must register first.
  r = post("/lease", {{"worker_id", "ghost"}}, wrk());
  EXPECT_EQ(r->status, 404);
  EXPECT_EQ(json::parse(r->body).at("path"), "/worker_id");
}

TEST_F(ServerTest, FailRecordsTheLogAndRetryFailedRequeues) {
  start();
  const int64_t job = submit(1, 8, 0, /*max_attempts=*/1);
  const std::string w = register_worker("w");
  const json l = lease(w);
  post_ok("/fail", {{"lease_id", l.at("lease_id")}, {"log", "renderer crashed: SIGSEGV"}}, wrk());
  EXPECT_EQ(post("/fail", {{"lease_id", l.at("lease_id")}, {"log", "again"}}, wrk())->status, 409);
  json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("counts").at("failed"), 1);
  const std::string task = j.at("tasks")[0].at("id").dump();
  auto r = client().Get(("/api/v1/jobs/" + std::to_string(job) + "/tasks/" + task + "/log").c_str(),
                        sub());
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, "renderer crashed: SIGSEGV");
  EXPECT_EQ(client()
                .Get(("/api/v1/jobs/" + std::to_string(job) + "/tasks/999/log").c_str(), sub())
                ->status,
            404);
  j = post_ok("/jobs/" + std::to_string(job) + "/retry-failed", json::object(), sub());
  EXPECT_EQ(j.at("requeued"), 1);
  EXPECT_EQ(j.at("job").at("counts").at("queued"), 1);
  EXPECT_EQ(post("/jobs/999/cancel", json::object(), sub())->status, 404);
  EXPECT_EQ(client().Get("/api/v1/jobs/999", sub())->status, 404);
  EXPECT_EQ(client().Get("/api/v1/jobs/abc", sub())->status, 404);
}

TEST_F(ServerTest, StaleLeaseIsRefusedAndNeverTouchesTheCommittedResult) {
  start();
  const int64_t job = submit(1);
  const std::string a = register_worker("a"), b = register_worker("b");
  const json la = lease(a);
  advance(11);  // a's lease (10 s) expired without a heartbeat
  const json lb = lease(b);
  ASSERT_TRUE(lb.contains("lease_id"));
  EXPECT_EQ(lb.at("task").at("id"), la.at("task").at("id"));
  EXPECT_EQ(lb.at("task").at("attempt"), 2);
  const std::string rb = put_blob("b's result");
  post_ok("/complete", {{"lease_id", lb.at("lease_id")}, {"result", rb}}, wrk());

  // The late calls of a's dead attempt are refused with 409.
  const std::string ra = put_blob("a's late result");
  auto r = post("/complete", {{"lease_id", la.at("lease_id")}, {"result", ra}}, wrk());
  EXPECT_EQ(r->status, 409) << r->body;
  EXPECT_EQ(json::parse(r->body).at("path"), "/lease_id");
  EXPECT_EQ(post("/heartbeat", {{"lease_id", la.at("lease_id")}}, wrk())->status, 409);
  EXPECT_EQ(post("/fail", {{"lease_id", la.at("lease_id")}, {"log", "x"}}, wrk())->status, 409);
  // Completing twice with the live lease is refused as well.
  EXPECT_EQ(post("/complete", {{"lease_id", lb.at("lease_id")}, {"result", ra}}, wrk())->status,
            409);

  const json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("tasks")[0].at("state"), "done");
  EXPECT_EQ(j.at("tasks")[0].at("result"), rb);
}

TEST_F(ServerTest, CancelAndPauseTakeEffectAtTheNextHeartbeat) {
  start();
  const int64_t job = submit(2);
  const std::string w = register_worker("w");
  const json l = lease(w);
  EXPECT_EQ(post_ok("/heartbeat", {{"lease_id", l.at("lease_id")}}, wrk()).at("answer"),
            "keep_running");
  const json c = post_ok("/jobs/" + std::to_string(job) + "/cancel", json::object(), sub());
  EXPECT_EQ(c.at("job").at("state"), "canceled");
  EXPECT_EQ(post_ok("/heartbeat", {{"lease_id", l.at("lease_id")}}, wrk()).at("answer"), "stop");
  const std::string res = put_blob("too late");
  EXPECT_EQ(post("/complete", {{"lease_id", l.at("lease_id")}, {"result", res}}, wrk())->status,
            409);
  EXPECT_EQ(post("/lease", {{"worker_id", w}}, wrk())->status, 204);

  const int64_t job2 = submit(1);
  const json l2 = lease(w);
  post_ok("/jobs/" + std::to_string(job2) + "/pause", json::object(), sub());
  EXPECT_EQ(post_ok("/heartbeat", {{"lease_id", l2.at("lease_id")}}, wrk()).at("answer"), "stop");
  EXPECT_EQ(post("/lease", {{"worker_id", w}}, wrk())->status, 204);
  const json r = post_ok("/jobs/" + std::to_string(job2) + "/resume", json::object(), sub());
  EXPECT_EQ(r.at("job").at("counts").at("queued"), 1);
  EXPECT_EQ(lease(w).at("task").at("job_id"), job2);
}

TEST_F(ServerTest, RestartOnTheSameDataDirKeepsCommittedStateAndLiveLeases) {
  start();
  const int64_t job = submit(2);
  const std::string w = register_worker("w");
  const json l1 = lease(w);
  const std::string r1 = put_blob("frame 1");
  post_ok("/complete", {{"lease_id", l1.at("lease_id")}, {"result", r1}}, wrk());
  const json l2 = lease(w);
  const std::string submitter = server_->submitter_token();

  start();  // stop, then a new server on the same data dir (same clock)
  EXPECT_EQ(server_->submitter_token(), submitter);
  json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("counts").at("done"), 1);
  EXPECT_EQ(j.at("counts").at("leased"), 1);
  EXPECT_EQ(j.at("tasks")[0].at("result"), r1);
  // The blob survived, the worker is still registered, the lease is still valid.
  EXPECT_EQ(client().Head(("/api/v1/blobs/" + r1).c_str(), wrk())->status, 200);
  EXPECT_EQ(get_ok("/workers").at("workers").size(), 1u);
  advance(5);
  EXPECT_EQ(post_ok("/heartbeat", {{"lease_id", l2.at("lease_id")}}, wrk()).at("answer"),
            "keep_running");
  const std::string r2 = put_blob("frame 2");
  post_ok("/complete", {{"lease_id", l2.at("lease_id")}, {"result", r2}}, wrk());
  EXPECT_EQ(post("/lease", {{"worker_id", w}}, wrk())->status, 204);
  j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("finished"), true);
  EXPECT_EQ(j.at("tasks")[1].at("result"), r2);
}

TEST_F(ServerTest, MetricsAreValidPrometheusText) {
  start();
  submit(3);
  const std::string w = register_worker("w");
  lease(w);
  client().Get("/api/v1/jobs");  // a 401
  auto r = client().Get("/metrics", sub());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->get_header_value("Content-Type").find("text/plain"), std::string::npos);
  const std::regex sample(
      R"(^([a-zA-Z_:][a-zA-Z0-9_:]*)(\{([a-zA-Z_][a-zA-Z0-9_]*="[^"\\]*")(,[a-zA-Z_][a-zA-Z0-9_]*="[^"\\]*")*\})? (-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?)$)");
  const std::regex comment(R"(^# (HELP|TYPE) [a-zA-Z_:][a-zA-Z0-9_:]* .+$)");
  std::map<std::string, double> values;
  std::istringstream in(r->body);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    std::smatch m;
    if (line.rfind("#", 0) == 0) {
      EXPECT_TRUE(std::regex_match(line, comment)) << line;
      continue;
    }
    ASSERT_TRUE(std::regex_match(line, m, sample)) << "not Prometheus text: '" << line << "'";
    values[m[1].str() + m[2].str()] = std::stod(m[5]);
    ++n;
  }
  EXPECT_GE(n, 9);
  EXPECT_EQ(values["vesper_jobs_total"], 1);
  EXPECT_EQ(values["vesper_tasks{state=\"queued\"}"], 2);
  EXPECT_EQ(values["vesper_tasks{state=\"leased\"}"], 1);
  EXPECT_EQ(values["vesper_tasks{state=\"failed\"}"], 0);
  EXPECT_EQ(values["vesper_leases_granted_total"], 1);
  EXPECT_EQ(values["vesper_workers"], 1);
  EXPECT_GE(values["vesper_http_requests_total{code=\"200\"}"], 2);  // register, lease
  EXPECT_EQ(values["vesper_http_requests_total{code=\"201\"}"], 2);  // blob, job
  EXPECT_GE(values["vesper_http_requests_total{code=\"401\"}"], 1);
}

TEST_F(ServerTest, RequestSizeLimitsAre413) {
  ServerConfig c = config();
  c.max_blob_bytes = 1 << 20;
  c.max_json_bytes = 16 << 10;
  start(c);
  const std::string big(c.max_blob_bytes + 1, 'x');
  auto r = client().Put(("/api/v1/blobs/" + sha256_hex(big)).c_str(), wrk(), big,
                        "application/octet-stream");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_EQ(client().Head(("/api/v1/blobs/" + sha256_hex(big)).c_str(), wrk())->status, 404);
  // At the limit is fine.
  const std::string fits(c.max_blob_bytes, 'y');
  r = client().Put(("/api/v1/blobs/" + sha256_hex(fits)).c_str(), wrk(), fits,
                   "application/octet-stream");
  EXPECT_EQ(r->status, 201);
  // JSON bodies have their own, smaller limit.
  const json body{
      {"name", std::string(c.max_json_bytes, 'n')}, {"scene", sha256_hex(fits)}, {"frames", "1"}};
  r = post("/jobs", body, sub());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_TRUE(json::parse(r->body).contains("error"));
  // The server still answers afterwards, on the same connection too.
  auto c2 = client();
  r = c2.Put(("/api/v1/blobs/" + sha256_hex(big)).c_str(), wrk(), big, "application/octet-stream");
  EXPECT_EQ(r->status, 413);
  EXPECT_EQ(c2.Get("/healthz")->status, 200);
  // Both kinds of 413 are counted.
  r = client().Get("/metrics", wrk());
  EXPECT_NE(r->body.find("vesper_http_requests_total{code=\"413\"} 3\n"), std::string::npos)
      << r->body;
}

TEST_F(ServerTest, ConcurrentWorkersNeverShareATask) {
  start();
  const int64_t job = submit(24, 8, 4);  // 48 tasks
  std::vector<std::string> ids;
  for (const char* name : {"w0", "w1", "w2", "w3", "w4", "w5"})
    ids.push_back(register_worker(name));
  std::mutex mu;
  std::map<int64_t, int> completed;  // task id -> times completed
  std::vector<std::thread> threads;
  for (const std::string& w : ids)
    threads.emplace_back([&, w] {
      httplib::Client c("127.0.0.1", port_);
      for (;;) {
        auto r = c.Post("/api/v1/lease", wrk(), json{{"worker_id", w}}.dump(), "application/json");
        if (!r || r->status != 200) break;
        const json l = json::parse(r->body);
        const std::string bytes = "result " + l.at("task").at("id").dump();
        c.Put(("/api/v1/blobs/" + sha256_hex(bytes)).c_str(), wrk(), bytes,
              "application/octet-stream");
        r = c.Post("/api/v1/complete", wrk(),
                   json{{"lease_id", l.at("lease_id")}, {"result", sha256_hex(bytes)}}.dump(),
                   "application/json");
        if (r && r->status == 200) {
          std::lock_guard lock(mu);
          ++completed[l.at("task").at("id").get<int64_t>()];
        }
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(completed.size(), 48u);
  for (const auto& [task, n] : completed) EXPECT_EQ(n, 1) << "task " << task;
  const json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("counts").at("done"), 48);
}

TEST_F(ServerTest, ExpiredLeasesAreRequeuedInTheBackground) {
  ServerConfig c = config();
  c.reaper_interval = 0.02;
  start(c);
  const int64_t job = submit(1);
  const json l = lease(register_worker("w"));
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(job)).at("counts").at("leased"), 1);
  advance(11);
  json j;
  for (int i = 0; i < 200; ++i) {
    j = get_ok("/jobs/" + std::to_string(job));
    if (j.at("counts").at("queued") == 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(j.at("counts").at("queued"), 1);  // without anyone asking for a lease
  EXPECT_EQ(j.at("tasks")[0].at("attempts"), 1);
  EXPECT_EQ(post("/heartbeat", {{"lease_id", l.at("lease_id")}}, wrk())->status, 409);
}

TEST_F(ServerTest, UnknownEndpointIsJson404) {
  start();
  auto r = client().Get("/api/v1/nope", sub());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_TRUE(json::parse(r->body).contains("error"));
}

}  // namespace
}  // namespace vesper
