// Farm housekeeping with real processes on 127.0.0.1: worker states
// (online, offline after a clean stop, lost after SIGKILL) and prune; `vesper
// delete` and blob GC over six tiny jobs; `submit --dry-run` uploads nothing;
// Ctrl-C on `vesper up` fetches the frames already done.
#include <fmt/format.h>
#include <signal.h>

#include <iostream>
#include <regex>
#include <set>

#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class OpsCliTest : public FarmTest {
 protected:
  // write_config's settings and no grace for unreferenced blobs.
  fs::path ops_config(double lease_seconds = 2) {
    const fs::path p = write_config(lease_seconds);
    std::string text = slurp(p);
    text.insert(text.find("[worker]"), "blob_grace_seconds = 0\n");
    std::ofstream(p) << text;
    return p;
  }
  json workers_json() {
    const RunResult r = farm("workers --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 ? json::parse(r.out) : json();
  }
  std::string state_of(const std::string& name) {
    const json all = workers_json();
    for (const json& w : all.value("workers", json::array()))
      if (w.at("name") == name) return w.value("state", "");
    return "";
  }
  // Polls until worker `name` is in `state`; false after `seconds`.
  bool wait_state(const std::string& name, const std::string& state, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (state_of(name) == state) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }
  // Blob files in the server's data dir (name -> size).
  std::map<std::string, uintmax_t> blob_files() {
    std::map<std::string, uintmax_t> out;
    for (const auto& e : fs::recursive_directory_iterator(dir_ / "data" / "blobs"))
      if (e.is_regular_file()) out[e.path().filename().string()] = e.file_size();
    return out;
  }
};

TEST_F(OpsCliTest, StoppedWorkerIsOfflineKilledOneLostAndPruneKeepsTheOnlineOne) {
  const auto config = ops_config(4);  // time to see the killed one online first
  start_server(config);
  start_worker("stays", config);
  BackgroundProcess& stopped = start_worker("stopped", config);
  BackgroundProcess& killed = start_worker("killed", config);
  for (const char* name : {"stays", "stopped", "killed"})
    ASSERT_TRUE(wait_state(name, "online", 20)) << name << ": " << worker_log(name);

  stopped.signal(SIGTERM);  // a clean stop says goodbye
  ASSERT_EQ(stopped.wait_for(20), 0) << worker_log("stopped");
  EXPECT_EQ(state_of("stopped"), "offline");
  killed.signal(SIGKILL);  // no goodbye: online until the lease time passes
  ASSERT_TRUE(killed.wait_for(10));
  EXPECT_EQ(state_of("killed"), "online");
  EXPECT_TRUE(wait_state("killed", "lost", 15));
  EXPECT_EQ(state_of("stays"), "online");
  const RunResult table = farm("workers");
  EXPECT_NE(table.out.find("offline"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("lost"), std::string::npos) << table.out;

  const RunResult prune = farm("workers --prune");
  EXPECT_EQ(prune.exit_code, 0) << prune.err;
  EXPECT_NE(prune.out.find("pruned 2 offline or lost worker(s)"), std::string::npos) << prune.out;
  EXPECT_NE(prune.out.find("  stopped "), std::string::npos) << prune.out;
  EXPECT_NE(prune.out.find("  killed "), std::string::npos) << prune.out;
  const json left = workers_json().at("workers");
  ASSERT_EQ(left.size(), 1u) << left.dump();
  EXPECT_EQ(left[0].at("name"), "stays");
}

// The issue's case: six tiny jobs. Deleting them all frees every blob they
// made (scene, mesh, results); deleting one keeps what the others share.
TEST_F(OpsCliTest, DeletingSixTinyJobsFreesExactlyTheirBlobs) {
  const auto config = ops_config();
  start_server(config);
  const auto scene = write_scene(16, 16, 1);
  std::vector<long long> jobs;
  for (int spp = 1; spp <= 6; ++spp)  // a different spp each: nothing is reused
    jobs.push_back(submit(fmt::format("{} --spp {}", scene.string(), spp)));
  const RunResult active = farm(fmt::format("delete {}", jobs[0]));
  EXPECT_EQ(active.exit_code, 1);
  EXPECT_NE(active.err.find("is active (1 queued, 0 running)"), std::string::npos) << active.err;

  start_worker("w", config);
  for (long long j : jobs) wait_finished(j, 120);
  const auto before = blob_files();
  uintmax_t total = 0;
  for (const auto& [name, size] : before) total += size;
  EXPECT_EQ(before.size(), 2u + 6u);  // scene and mesh, shared; six results

  int64_t blobs = 0;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const RunResult r = farm(fmt::format("delete {}", jobs[i]));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find(fmt::format("deleted job {}", jobs[i])), std::string::npos) << r.err;
    const std::regex said(R"((\d+) blob\(s\) freed)");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.err, m, said)) << r.err;
    blobs += std::stoll(m[1]);
    // The shared scene and mesh stay until the last job goes.
    EXPECT_EQ(blob_files().size(), before.size() - blobs) << r.err;
    if (i + 1 < jobs.size()) {
      EXPECT_EQ(std::stoll(m[1]), 1) << r.err;
    }
  }
  EXPECT_TRUE(blob_files().empty());
  EXPECT_EQ(blobs, int64_t(before.size()));
  // The figure for the report: what six tiny jobs left, all of it freed.
  std::cout << "six tiny jobs: " << before.size() << " blobs, " << total << " bytes; freed all\n";
}

TEST_F(OpsCliTest, DryRunLeavesTheBlobDirUnchanged) {
  const auto config = ops_config();
  start_server(config);
  const auto scene = write_scene(16, 16, 1);
  const auto before = blob_files();
  const RunResult r = farm("submit " + scene.string() + " --frames 1-3 --dry-run");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("would make 3 tasks"), std::string::npos) << r.err;
  EXPECT_EQ(blob_files(), before);
  EXPECT_EQ(farm("status").out, "no jobs\n");
}

// Ctrl-C once the first frame is done: `up` fetches the frames done by then
// (and those its worker finishes), names the missing ones and exits 130.
TEST_F(OpsCliTest, CtrlCOnUpFetchesTheFramesAlreadyDone) {
  const auto scene = write_scene(48, 48, 8);
  const fs::path data = dir_ / "up-data", frames = dir_ / "up-frames";
  BackgroundProcess up(
      {VESPER_BINARY, "up", "--scene", scene.string(), "--frames", "1-40", "--workers", "1",
       "--no-comp", "--data-dir", data.string(), "-o", frames.string()},
      dir_ / "up.out", dir_ / "up.log");
  const std::regex url_line(R"(http://127\.0\.0\.1:(\d+))");
  std::smatch m;
  std::string log;
  for (int i = 0; i < 500 && !std::regex_search(log, m, url_line); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    log = slurp(dir_ / "up.log");
  }
  ASSERT_FALSE(m.empty()) << log;
  httplib::Client c("127.0.0.1", std::stoi(m[1]));
  c.set_bearer_token_auth(json::parse(slurp(data / "tokens.json")).at("submitter"));
  bool done = false;
  for (int i = 0; i < 1200 && !done; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    auto r = c.Get("/api/v1/jobs/1/frames");
    if (!r || r->status != 200) continue;
    const json frames_now = json::parse(r->body);
    for (const json& f : frames_now.at("frames")) done = done || f.at("state") == "ready";
  }
  ASSERT_TRUE(done) << slurp(dir_ / "up.log");
  up.signal(SIGINT);
  ASSERT_EQ(up.wait_for(60), 130) << slurp(dir_ / "up.log");

  const std::string out = slurp(dir_ / "up.out");
  std::set<std::string> written;
  for (const auto& e : fs::directory_iterator(frames)) written.insert(e.path().string());
  EXPECT_GE(written.size(), 1u);
  EXPECT_LT(written.size(), 40u) << "the test wants Ctrl-C before the job ends";
  for (const std::string& f : written) {
    EXPECT_NE(out.find(f), std::string::npos) << f << " not printed";
    EXPECT_EQ(f.substr(f.size() - 4), ".exr");
  }
  const std::string err = slurp(dir_ / "up.log");
  EXPECT_NE(err.find(fmt::format("fetched {} finished frame(s)", written.size())),
            std::string::npos)
      << err;
  EXPECT_NE(err.find(fmt::format("missing frames: {}-40", written.size() + 1)), std::string::npos)
      << err;
  EXPECT_EQ(err.find("missing frames: none"), std::string::npos) << err;
}

}  // namespace
}  // namespace vesper::test
