// Deleting jobs and collecting their blobs (DELETE /jobs/{id}), and the
// workers' states (online, offline, lost), current task, blocklists, prune.
#include <filesystem>

#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

namespace fs = std::filesystem;

class HousekeepingTest : public ServerTest {
 protected:
  ServerConfig config_with_grace(double grace) const {
    ServerConfig c = config();
    c.blob_grace_seconds = grace;
    return c;
  }
  fs::path blob_file(const std::string& hash) const {
    return dir_ / "data" / "blobs" / hash.substr(0, 2) / hash.substr(2);
  }
  httplib::Result del(const std::string& path) {
    return client().Delete(("/api/v1" + path).c_str(), sub());
  }
  json del_ok(const std::string& path) {
    auto r = del(path);
    EXPECT_TRUE(r);
    if (!r) return {};
    EXPECT_EQ(r->status, 200) << path << ": " << r->body;
    return json::parse(r->body);
  }
  // Leases the next task and completes it with `result` (uploaded here).
  void complete_next(const std::string& worker, const std::string& result) {
    const json l = lease(worker);
    post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", put_blob(result)}}, wrk());
  }
  json worker_entry(const std::string& id) {
    const json all = get_ok("/workers");
    for (const json& w : all.at("workers"))
      if (w.at("worker_id") == id) return w;
    return {};
  }
};

TEST_F(HousekeepingTest, DeleteRefusesAnActiveJobNamingItsState) {
  start();
  const int64_t job = submit(2);
  auto r = del("/jobs/" + std::to_string(job));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
  const std::string error = json::parse(r->body).at("error");
  EXPECT_NE(error.find("is active (2 queued, 0 running)"), std::string::npos) << error;
  EXPECT_NE(error.find("cancel it first"), std::string::npos) << error;
  // A running task also keeps it.
  lease(register_worker("w"));
  r = del("/jobs/" + std::to_string(job));
  EXPECT_EQ(r->status, 409);
  post_ok("/jobs/" + std::to_string(job) + "/cancel", json::object(), sub());
  const json d = del_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(d.at("deleted"), job);
  EXPECT_EQ(client().Get(("/api/v1/jobs/" + std::to_string(job)).c_str(), sub())->status, 404);
  EXPECT_EQ(del("/jobs/" + std::to_string(job))->status, 404);
  EXPECT_TRUE(get_ok("/jobs").at("jobs").empty());
}

// Two jobs share their scene; each has its own result. Deleting the first
// frees its result only; deleting the second frees the rest.
TEST_F(HousekeepingTest, GcRemovesExactlyTheBlobsNoJobReferences) {
  start(config_with_grace(0));
  const std::string w = register_worker("w");
  const int64_t a = submit(1), b = submit(1);  // the same scene bytes
  const std::string scene = sha256_hex("{\"format\": \"vesper-scene/1\"}");
  complete_next(w, "result of a");
  complete_next(w, "result of b");
  ASSERT_TRUE(fs::exists(blob_file(scene)));

  const json first = del_ok("/jobs/" + std::to_string(a));
  EXPECT_EQ(first.at("blobs_freed"), 1);
  EXPECT_EQ(first.at("bytes_freed"), int64_t(std::string("result of a").size()));
  EXPECT_FALSE(fs::exists(blob_file(sha256_hex("result of a"))));
  EXPECT_TRUE(fs::exists(blob_file(scene))) << "b still uses the scene";
  EXPECT_TRUE(fs::exists(blob_file(sha256_hex("result of b"))));
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(b) + "/frames").at("frames")[0].at("state"), "ready");

  const json second = del_ok("/jobs/" + std::to_string(b));
  EXPECT_EQ(second.at("blobs_freed"), 2);
  EXPECT_FALSE(fs::exists(blob_file(scene)));
  EXPECT_FALSE(fs::exists(blob_file(sha256_hex("result of b"))));
}

// Clients upload before they submit: an upload no job references yet (and a
// blob a client asked about with HEAD) survives a collection within the
// grace; the deleted job's own inputs do not wait for it.
TEST_F(HousekeepingTest, UnreferencedUploadSurvivesWithinTheGrace) {
  start(config_with_grace(3600));
  const std::string fresh = put_blob("about to be submitted");
  const int64_t job = submit(1);
  const std::string scene = sha256_hex("{\"format\": \"vesper-scene/1\"}");
  post_ok("/jobs/" + std::to_string(job) + "/cancel", json::object(), sub());
  const json d = del_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(d.at("blobs_freed"), 1);
  EXPECT_FALSE(fs::exists(blob_file(scene)));
  EXPECT_TRUE(fs::exists(blob_file(fresh)));

  // Without a grace the same upload is collected by the next deletion.
  start(config_with_grace(0));
  const int64_t other = submit(1);
  post_ok("/jobs/" + std::to_string(other) + "/cancel", json::object(), sub());
  EXPECT_EQ(del_ok("/jobs/" + std::to_string(other)).at("blobs_freed"), 2);
  EXPECT_FALSE(fs::exists(blob_file(fresh)));
}

// Pending marks live in memory: after a restart a blob is pending from its
// file's mtime, so a fresh upload still survives; a job's blobs do not wait.
TEST_F(HousekeepingTest, ARestartKeepsAFreshUploadPending) {
  start(config_with_grace(3600));
  const std::string fresh = put_blob("uploaded before the restart");
  const int64_t job = submit(1);
  post_ok("/jobs/" + std::to_string(job) + "/cancel", json::object(), sub());
  start(config_with_grace(3600));
  EXPECT_EQ(del_ok("/jobs/" + std::to_string(job)).at("blobs_freed"), 1);  // its scene
  EXPECT_TRUE(fs::exists(blob_file(fresh)));
}

TEST_F(HousekeepingTest, HeadMarksAStoredBlobPendingAgain) {
  start(config_with_grace(3600));
  const int64_t job = submit(1);
  const std::string scene = sha256_hex("{\"format\": \"vesper-scene/1\"}");
  post_ok("/jobs/" + std::to_string(job) + "/cancel", json::object(), sub());
  // A client about to submit the same scene asks whether the server has it.
  auto h = client().Head(("/api/v1/blobs/" + scene).c_str(), sub());
  ASSERT_TRUE(h);
  EXPECT_EQ(h->status, 200);
  EXPECT_EQ(del_ok("/jobs/" + std::to_string(job)).at("blobs_freed"), 0);
  EXPECT_TRUE(fs::exists(blob_file(scene)));
}

TEST_F(HousekeepingTest, WorkerStatesCurrentTaskAndBlocklists) {
  start();  // lease_seconds 10
  const std::string stopped = register_worker("stopped");
  const std::string killed = register_worker("killed");
  const std::string busy = register_worker("busy");
  EXPECT_EQ(worker_entry(stopped).at("state"), "online");
  post_ok("/workers/goodbye", {{"worker_id", stopped}}, wrk());
  EXPECT_EQ(worker_entry(stopped).at("state"), "offline");

  const int64_t job = submit(4, 8, 0, 5);
  for (int i = 0; i < 3; ++i) {  // three distinct tasks failed: blocked for the job
    const json l = lease(busy);
    post_ok("/fail", {{"lease_id", l.at("lease_id")}, {"log", "boom"}}, wrk());
  }
  const int64_t other = submit(1);
  const json l = lease(busy);
  EXPECT_EQ(l.at("task").at("job_id"), other);
  json b = worker_entry(busy);
  EXPECT_EQ(b.at("current_task").at("job"), other);
  EXPECT_EQ(b.at("current_task").at("task"), l.at("task").at("id"));
  EXPECT_EQ(b.at("blocklisted_for"), json::array({job}));
  EXPECT_FALSE(worker_entry(killed).contains("current_task"));
  EXPECT_FALSE(worker_entry(killed).contains("blocklisted_for"));

  advance(6);
  post_ok("/heartbeat", {{"lease_id", l.at("lease_id")}}, wrk());  // `busy` is seen
  advance(5);  // `killed` said nothing for longer than the lease time
  EXPECT_EQ(worker_entry(killed).at("state"), "lost");
  EXPECT_EQ(worker_entry(stopped).at("state"), "offline");
  EXPECT_EQ(worker_entry(busy).at("state"), "online");

  const json pruned = post_ok("/workers/prune", json::object(), sub());
  EXPECT_EQ(pruned.at("pruned").size(), 2u);
  const json left = get_ok("/workers").at("workers");
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].at("worker_id"), busy);
  // A goodbye from a worker the server does not know is a 404.
  EXPECT_EQ(post("/workers/goodbye", {{"worker_id", killed}}, wrk())->status, 404);
}

}  // namespace
}  // namespace vesper
