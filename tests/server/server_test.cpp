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

#include "common/sha256.h"
#include "server/server.h"
#include "tests/common/temp_dir.h"
#include "tests/server/server_fixture.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

// Two servers must never share a port (SO_REUSEPORT would let the second one
// silently take half the requests), and a restart on the port must work.
TEST_F(ServerTest, ASecondServerOnTheSamePortFailsToStart) {
  start();
  ServerConfig other = config();
  other.data_dir = dir_ / "other";
  other.port = port_;
  Server second(other);
  EXPECT_THROW(second.start(), std::runtime_error);
  // The first one still serves.
  auto r = client().Get("/healthz");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  // ... and after it stops, a new server takes the port at once.
  const int port = port_;
  server_.reset();
  ServerConfig again = config();
  again.port = port;
  start(again);
  EXPECT_EQ(port_, port);
}

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

// Leases carry the worker's renderer id (sha256 of its executable); an
// identical task already done by a trusted renderer is completed at submit,
// never leased.
TEST_F(ServerTest, LeaseWithARendererIdReusesIdenticalResults) {
  const std::string renderer(64, 'a');
  ServerConfig c = config();
  c.trusted_renderers = {renderer};  // registered by the operator
  start(c);
  const std::string w = register_worker("box-1");
  auto bad = post("/lease", {{"worker_id", w}, {"renderer", "../x"}}, wrk());
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(json::parse(bad->body).at("path"), "/renderer");

  const int64_t first = submit(1);
  const json l = post_ok("/lease", {{"worker_id", w}, {"renderer", renderer}}, wrk());
  const std::string result = put_blob("the frame");
  post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", result}}, wrk());
  const int64_t second = submit(1);  // same scene blob, frames, spp
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(second)).at("state"), "done") << "at submit";
  auto none = post("/lease", {{"worker_id", w}, {"renderer", renderer}}, wrk());
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 204) << "the identical task should not be leased";
  const json j = get_ok("/jobs/" + std::to_string(second));
  EXPECT_EQ(j.at("counts").at("done"), 1);
  EXPECT_EQ(j.at("tasks").at(0).at("result"), result);
  EXPECT_EQ(j.at("tasks").at(0).at("reused_from"),
            get_ok("/jobs/" + std::to_string(first)).at("tasks").at(0).at("id"));
  auto m = client().Get("/metrics", wrk());
  EXPECT_NE(m->body.find("vesper_tasks_reused_total 1"), std::string::npos) << m->body;
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
  EXPECT_EQ(j.at("state"), "done");
  EXPECT_TRUE(j.contains("finished"));
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(j.at("tasks")[i].at("result"), results[i]);
  const json jobs = get_ok("/jobs").at("jobs");
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].at("state"), "done");

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

// Cancel stops the running render at its next heartbeat; pause stops
// leasing and lets running tasks finish (their results are taken).
TEST_F(ServerTest, CancelStopsAtTheNextHeartbeatAndPauseLetsRunningTasksFinish) {
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

  const int64_t job2 = submit(2);
  const json l2 = lease(w);
  const json p = post_ok("/jobs/" + std::to_string(job2) + "/pause", json::object(), sub());
  EXPECT_EQ(p.at("job").at("state"), "paused");
  EXPECT_EQ(post_ok("/heartbeat", {{"lease_id", l2.at("lease_id")}}, wrk()).at("answer"),
            "keep_running");
  EXPECT_EQ(post("/lease", {{"worker_id", w}}, wrk())->status, 204);
  post_ok("/complete", {{"lease_id", l2.at("lease_id")}, {"result", put_blob("kept")}}, wrk());
  const json r = post_ok("/jobs/" + std::to_string(job2) + "/resume", json::object(), sub());
  EXPECT_EQ(r.at("job").at("counts").at("queued"), 1);
  EXPECT_EQ(r.at("job").at("counts").at("done"), 1);
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
  EXPECT_EQ(j.at("state"), "done");
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

TEST_F(ServerTest, AssetsAreValidatedNamingTheJsonPath) {
  start();
  const std::string scene = put_blob("scene");
  const std::string a = put_blob("mesh a"), b = put_blob("mesh b");
  const json good{
      {"scene", scene},
      {"frames", "1"},
      {"assets", {{{"name", "assets/a.obj"}, {"blob", a}}, {{"name", "b.obj"}, {"blob", b}}}}};
  struct Case {
    json assets;
    std::string path;
  };
  auto one = [&](const std::string& name) {
    return json::array({{{"name", "ok.obj"}, {"blob", a}}, {{"name", name}, {"blob", b}}});
  };
  const std::vector<Case> cases = {
      {one("../x"), "/assets/1/name"},
      {one("/etc/passwd"), "/assets/1/name"},
      {one("a/../../b"), "/assets/1/name"},
      {one("a//b"), "/assets/1/name"},
      {one("a/./b"), "/assets/1/name"},
      {one("a\\b"), "/assets/1/name"},
      {one(std::string("a\0b", 3)), "/assets/1/name"},
      {one(""), "/assets/1/name"},
      {one("dir/"), "/assets/1/name"},
      {one(std::string(256, 'x')), "/assets/1/name"},
      {one("scene.json"), "/assets/1/name"},
      {one("ok.obj"), "/assets/1/name"},        // duplicate
      {one("ok.obj/inner"), "/assets/0/name"},  // a file and a directory at once
      {json::array({{{"name", "a.obj"}, {"blob", a}},
                    {{"name", "b.obj"}, {"blob", a}},
                    {{"name", "c.obj"}, {"blob", a}},
                    {{"name", "d.obj"}, {"blob", sha256_hex("never uploaded")}}}),
       "/assets/3/blob"},
      {json::array({{{"name", "a.obj"}, {"blob", "A" + a.substr(1)}}}), "/assets/0/blob"},
      {json::array({{{"name", "a.obj"}, {"blob", 5}}}), "/assets/0/blob"},
      {json::array({{{"name", "a.obj"}}}), "/assets/0/blob"},
      {json::array({{{"name", 3}, {"blob", a}}}), "/assets/0/name"},
      {json::array({{{"name", "a.obj"}, {"blob", a}, {"size", 3}}}), "/assets/0/size"},
      {json::array({"a.obj"}), "/assets/0"},
      {json{{"a.obj", a}}, "/assets"},
  };
  for (const Case& k : cases) {
    json body = good;
    body["assets"] = k.assets;
    for (const char* query : {"", "?dry_run=1"}) {
      auto r = client().Post((std::string("/api/v1/jobs") + query).c_str(), sub(), body.dump(),
                             "application/json");
      ASSERT_TRUE(r);
      // A dry run needs no uploaded blobs (`vesper submit --dry-run` uploads none).
      if (*query && k.path == "/assets/3/blob") {
        EXPECT_EQ(r->status, 200) << r->body;
        continue;
      }
      EXPECT_EQ(r->status, 400) << k.assets.dump() << query << ": " << r->body;
      const json e = json::parse(r->body);
      EXPECT_EQ(e.value("path", ""), k.path) << k.assets.dump() << ": " << r->body;
      EXPECT_FALSE(e.value("error", "").empty());
    }
  }
  EXPECT_TRUE(get_ok("/jobs").at("jobs").empty());
  auto r = client().Post("/api/v1/jobs?dry_run=1", sub(), good.dump(), "application/json");
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(post("/jobs", good, sub())->status, 201);
}

TEST_F(ServerTest, LeaseCarriesTheAssets) {
  start();
  const std::string scene = put_blob("scene");
  const std::string a = put_blob("mesh a"), b = put_blob("vdb b");
  const json assets =
      json::array({{{"name", "meshes/a.obj"}, {"blob", a}}, {{"name", "smoke.vdb"}, {"blob", b}}});
  post_ok("/jobs", {{"scene", scene}, {"frames", "1"}, {"assets", assets}}, sub(), 201);
  const std::string w = register_worker("w");
  const json l = lease(w);
  EXPECT_EQ(l.at("assets"), assets);
  // A job without assets leases an empty list.
  const int64_t other = submit(1);
  (void)other;
  const json m = lease(w);
  EXPECT_EQ(m.at("assets"), json::array());
}

// A stand-in for `vesper merge -o OUT IN... -q`: logs each run to `runs`,
// concatenates its inputs after `seconds` (or fails with `exit_code` and a
// message on stderr).
fs::path fake_merger(const fs::path& dir, const std::string& name, double seconds,
                     int exit_code = 0) {
  fs::create_directories(dir);
  const fs::path script = dir / name;
  std::ofstream f(script);
  f << "#!/bin/sh\n"
    << "echo run >> '" << (dir / (name + ".runs")).string() << "'\n"
    << "[ \"$1\" = merge ] && [ \"$2\" = -o ] || exit 9\n"
    << "out=\"$3\"; shift 3\n"
    << "sleep " << seconds << "\n";
  if (exit_code != 0) {
    f << "echo 'boom: cannot merge these partials' >&2\nexit " << exit_code << "\n";
  } else {
    f << ": > \"$out.tmp\"\n"
      << "for a in \"$@\"; do [ \"$a\" = -q ] || cat \"$a\" >> \"$out.tmp\"; done\n"
      << "mv \"$out.tmp\" \"$out\"\n";
  }
  f.close();
  fs::permissions(script, fs::perms::owner_all);
  return script;
}

int runs_of(const fs::path& script) {
  std::ifstream in(script.string() + ".runs");
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

class FrameTest : public ServerTest {
 protected:
  // Completes every queued task of the job with the result "result of task
  // <id>"; returns the results by task id.
  std::map<int64_t, std::string> complete_all() {
    const std::string w = register_worker("w");
    std::map<int64_t, std::string> results;
    for (;;) {
      auto r = post("/lease", {{"worker_id", w}}, wrk());
      if (!r || r->status != 200) break;
      const json l = json::parse(r->body);
      const int64_t id = l.at("task").at("id");
      results[id] = "result of task " + std::to_string(id);
      post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", put_blob(results[id])}},
              wrk());
    }
    return results;
  }
  httplib::Result frame(int64_t job, int frame) {
    return client().Get(
        ("/api/v1/jobs/" + std::to_string(job) + "/frames/" + std::to_string(frame)).c_str(),
        sub());
  }
  json frames(int64_t job) {
    return get_ok("/jobs/" + std::to_string(job) + "/frames").at("frames");
  }
  // Waits until the listing shows `frame` in `state`.
  bool wait_for_state(int64_t job, size_t index, const std::string& state) {
    for (int i = 0; i < 200; ++i) {
      if (frames(job).at(index).at("state") == state) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    }
    return false;
  }
};

TEST_F(FrameTest, AOneTaskFrameIsItsResultAndNeedsNoMerge) {
  start();  // no vesper binary next to the test: merging is unavailable
  const int64_t job = submit(2);
  auto r = frame(job, 1);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409) << r->body;
  EXPECT_NE(json::parse(r->body).at("error").get<std::string>().find("not finished"),
            std::string::npos);
  EXPECT_EQ(frames(job), json::parse(R"([{"frame": 1, "state": "pending", "tasks": 1, "done": 0},
                                          {"frame": 2, "state": "pending", "tasks": 1, "done": 0}])"));
  const auto results = complete_all();
  ASSERT_EQ(results.size(), 2u);
  const json f = frames(job);
  EXPECT_EQ(f.at(0).at("state"), "ready");
  EXPECT_EQ(f.at(0).at("blob"), sha256_hex(results.begin()->second));
  r = frame(job, 1);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->body, results.begin()->second);
  EXPECT_EQ(r->get_header_value("Content-Type"), "image/x-exr");
  // Unknown frame, job, malformed frame: 404. The worker token cannot read frames.
  EXPECT_EQ(frame(job, 3)->status, 404);
  EXPECT_EQ(frame(job + 1, 1)->status, 404);
  EXPECT_EQ(
      client().Get(("/api/v1/jobs/" + std::to_string(job) + "/frames/x").c_str(), sub())->status,
      404);
  EXPECT_EQ(
      client().Get(("/api/v1/jobs/" + std::to_string(job) + "/frames").c_str(), wrk())->status,
      401);
}

TEST_F(FrameTest, WithoutAVesperBinaryASplitFrameIs503) {
  start();
  const int64_t job = submit(1, 8, 4);
  complete_all();
  auto r = frame(job, 1);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503) << r->body;
  EXPECT_NE(json::parse(r->body).at("error").get<std::string>().find("vesper"), std::string::npos);
  EXPECT_EQ(frames(job).at(0).at("state"), "pending");
}

TEST_F(FrameTest, ASplitFrameIsMergedOnceEvenWhenRequestsRace) {
  ServerConfig c = config();
  c.vesper_binary = fake_merger(dir_ / "bin", "vesper", 0.3);
  start(c);
  const int64_t job = submit(1, 8, 2);  // 4 tasks
  auto r = frame(job, 1);
  EXPECT_EQ(r->status, 409);
  const auto results = complete_all();  // the background merge starts
  ASSERT_EQ(results.size(), 4u);
  std::string expected;  // the fake concatenates in sample order (= task id order here)
  for (const auto& [id, bytes] : results) expected += bytes;
  std::vector<std::thread> threads;
  std::vector<std::string> got(4);
  for (int i = 0; i < 4; ++i)
    threads.emplace_back([&, i] {
      auto res = frame(job, 1);
      got[size_t(i)] = res ? std::to_string(res->status) + ":" + res->body : "no answer";
    });
  for (auto& t : threads) t.join();
  for (const std::string& g : got) EXPECT_EQ(g, "200:" + expected);
  EXPECT_EQ(runs_of(c.vesper_binary), 1);
  const json f = frames(job);
  EXPECT_EQ(f.at(0).at("state"), "ready");
  EXPECT_EQ(f.at(0).at("blob"), sha256_hex(expected));
  // Recorded: a restarted server serves it without merging again.
  start(c);
  EXPECT_EQ(frame(job, 1)->body, expected);
  EXPECT_EQ(runs_of(c.vesper_binary), 1);
  EXPECT_TRUE(fs::is_empty(dir_ / "data" / "merge-tmp"));
}

TEST_F(FrameTest, TheMergeRunsInTheBackgroundAfterTheLastTask) {
  ServerConfig c = config();
  c.vesper_binary = fake_merger(dir_ / "bin", "vesper", 0);
  start(c);
  const int64_t job = submit(2, 8, 4);
  complete_all();
  EXPECT_TRUE(wait_for_state(job, 0, "ready"));
  EXPECT_TRUE(wait_for_state(job, 1, "ready"));
  EXPECT_EQ(runs_of(c.vesper_binary), 2);
}

TEST_F(FrameTest, AFailedMergeIs500WithItsStderrAndIsNotRetriedInALoop) {
  ServerConfig c = config();
  c.vesper_binary = fake_merger(dir_ / "bin", "vesper", 0, 3);
  c.merge_retry_seconds = 0.5;
  start(c);
  const int64_t job = submit(1, 8, 4);
  complete_all();
  EXPECT_TRUE(wait_for_state(job, 0, "failed"));
  EXPECT_NE(frames(job).at(0).at("error").get<std::string>().find("boom"), std::string::npos);
  auto r = frame(job, 1);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 500) << r->body;
  const std::string error = json::parse(r->body).at("error");
  EXPECT_NE(error.find("exit code 3"), std::string::npos) << error;
  EXPECT_NE(error.find("boom: cannot merge these partials"), std::string::npos) << error;
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(runs_of(c.vesper_binary), 1);  // not retried yet
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  EXPECT_EQ(frame(job, 1)->status, 500);  // retried on request after merge_retry_seconds
  EXPECT_EQ(runs_of(c.vesper_binary), 2);
}

TEST_F(FrameTest, AMergeKilledWithTheServerRecordsNothingAndIsRedoneAfterARestart) {
  ServerConfig slow = config();
  slow.vesper_binary = fake_merger(dir_ / "bin", "slow", 30);
  start(slow);
  const int64_t job = submit(1, 8, 4);
  const auto results = complete_all();
  for (int i = 0; i < 200 && runs_of(slow.vesper_binary) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  ASSERT_EQ(runs_of(slow.vesper_binary), 1);  // the merge is running
  const auto stopped_at = std::chrono::steady_clock::now();
  server_.reset();  // stops the server, killing the merge
  EXPECT_LT(std::chrono::steady_clock::now() - stopped_at, std::chrono::seconds(10));
  ServerConfig fast = config();
  fast.vesper_binary = fake_merger(dir_ / "bin", "fast", 0);
  start(fast);
  EXPECT_TRUE(wait_for_state(job, 0, "ready"));  // redone by the background merger at start
  std::string expected;
  for (const auto& [id, bytes] : results) expected += bytes;
  auto r = frame(job, 1);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->body, expected);
  EXPECT_EQ(runs_of(fast.vesper_binary), 1);
}

}  // namespace
}  // namespace vesper
