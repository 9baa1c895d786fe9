// Farm hardening end to end (docs/farm.md, "Hardening"): real `vesper server`
// and `vesper worker` processes on 127.0.0.1 against hostile names, scenes
// and renders, and an unlucky operator restarting the server mid-upload.
#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "common/sha256.h"
#include "jobs/job_store.h"
#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;

// Lines of a worker's log saying it registered.
int count_registrations(const std::string& log) {
  int n = 0;
  for (size_t at = log.find("registered as"); at != std::string::npos;
       at = log.find("registered as", at + 1))
    ++n;
  return n;
}

// Every file under `dir`, recursively, relative to it.
std::vector<std::string> files_under(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it); ++it)
    if (!it->is_directory()) out.push_back(fs::relative(it->path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

// Job names become file names in `vesper fetch`: nothing is written outside
// -o whatever the name. Names printed by `status` and `workers` have their
// control characters escaped (here from a store written by an older server
// that did not refuse them).
TEST_F(FarmTest, JobNamesStayInsideTheFetchFolderAndNamesAreEscaped) {
  const auto config = write_config(10);
  const auto scene = write_scene(16, 12, 1);
  fs::create_directories(dir_ / "data");
  {
    JobStore old(dir_ / "data" / "jobs.sqlite");
    JobSpec spec;
    spec.name = "evil\x1b[31m\nname";
    spec.scene = std::string(64, 'a');
    spec.frames = {1};
    old.pause(old.submit(spec, 0));
  }
  std::ofstream(dir_ / "data" / "workers.json")
      << R"({"workers": [{"worker_id": "0123", "name": "w\u001b[2J\r", "registered": 1,)"
      << R"( "last_seen": 1}]})";
  start_server(config);
  start_worker("w1", config);
  const fs::path outside = dir_ / "abs" / "dir";
  fs::create_directories(outside);
  const std::vector<std::string> names = {"../../escaped", (outside / "x").string(), "..", "a####"};
  for (const std::string& name : names) {
    const long long id = submit(fmt::format("{} --frames 1 --name '{}'", scene.string(), name));
    ASSERT_GT(id, 0) << name;
    ASSERT_EQ(wait_finished(id, 120).at("counts").at("done"), 1) << name;
    const fs::path out = dir_ / "out" / std::to_string(id);
    const RunResult f = farm(fmt::format("fetch {} -o {}", id, out.string()));
    EXPECT_EQ(f.exit_code, 0) << f.err;
    const auto files = files_under(out);
    ASSERT_EQ(files.size(), 1u) << name;
    EXPECT_EQ(files[0].find('/'), std::string::npos) << files[0];
    EXPECT_NE(files[0].rfind(".0001.exr"), std::string::npos) << files[0];
    EXPECT_NE(files[0][0], '.') << files[0];
  }
  EXPECT_TRUE(files_under(outside).empty());
  EXPECT_FALSE(fs::exists(dir_ / "escaped.0001.exr"));
  EXPECT_EQ(files_under(dir_ / "out").size(), names.size());

  const RunResult all = farm("status");
  EXPECT_EQ(all.exit_code, 0) << all.err;
  EXPECT_NE(all.out.find("evil\\x1b[31m\\nname"), std::string::npos) << all.out;
  const RunResult w = farm("workers");
  EXPECT_EQ(w.exit_code, 0) << w.err;
  EXPECT_NE(w.out.find("w\\x1b[2J\\r"), std::string::npos) << w.out;
  for (const RunResult& r : {all, w, farm("status 1")}) {
    EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find('\r'), std::string::npos) << r.out;
  }
}

// A worker restarted on the same cache dir (here killed with SIGKILL each
// time) registers again with the id it had: the server keeps one entry for
// it (workers.json did grow by one per restart).
TEST_F(FarmTest, ARestartedWorkerKeepsItsIdAndWorkersJsonDoesNotGrow) {
  const auto config = write_config(10);
  start_server(config);
  std::set<std::string> ids;
  for (int run = 0; run < 4; ++run) {
    auto& w = start_worker("same", config);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (count_registrations(worker_log("same")) < 1 &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const std::string log = worker_log("same");
    const size_t at = log.find(" as ");
    ASSERT_NE(at, std::string::npos) << log;
    ids.insert(log.substr(at + 4, 32));
    w.signal(SIGKILL);
    ASSERT_TRUE(w.wait_for(5));
  }
  EXPECT_EQ(ids.size(), 1u);
  const auto doc = nlohmann::json::parse(slurp(dir_ / "data" / "workers.json"));
  EXPECT_EQ(doc.at("workers").size(), 1u) << doc.dump();
}

// The worker checks again what the server checked at submit: a job whose
// scene references a file outside the task directory (here put in the store
// as an older server would have accepted it) fails on the worker with a log
// naming the JSON path and the file, and the file is never read. A local
// `vesper render` of one's own scene keeps its absolute paths.
TEST_F(FarmTest, AWorkerRefusesSceneFilesOutsideTheTaskDirectory) {
  const auto config = write_config(10);
  const fs::path scene = write_scene(16, 12, 1);  // the cube mesh by absolute path
  const std::string text = slurp(scene);
  const std::string sha = sha256_hex(text);
  const fs::path blob = dir_ / "data" / "blobs" / sha.substr(0, 2) / sha.substr(2);
  fs::create_directories(blob.parent_path());
  std::ofstream(blob) << text;
  {
    JobStore old(dir_ / "data" / "jobs.sqlite");
    JobSpec spec;
    spec.name = "outside";
    spec.scene = sha;
    spec.frames = {1};
    spec.spp = 1;
    spec.max_attempts = 1;
    old.submit(spec, 0);
  }
  start_server(config);
  start_worker("w1", config);
  const auto j = wait_finished(1, 120);
  EXPECT_EQ(j.at("counts").at("failed"), 1) << j.dump();
  const RunResult logs = farm("logs 1");
  EXPECT_EQ(logs.exit_code, 0) << logs.err;
  EXPECT_NE(logs.out.find("/shapes/"), std::string::npos) << logs.out;
  EXPECT_NE(logs.out.find("cube.obj' is an absolute path"), std::string::npos) << logs.out;
  EXPECT_NE(logs.out.find("exit code 2"), std::string::npos) << logs.out;

  const std::string render = "render " + scene.string() + " -o " + (dir_ / "local.exr").string();
  EXPECT_EQ(run(render + " -q").exit_code, 0);
  const RunResult refused = run(render + " --scene-dir-only -q");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("is an absolute path"), std::string::npos) << refused.err;
}

// True while `pid` is a live process (not gone, not a zombie).
bool alive(long pid) {
  const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
  const size_t paren = stat.rfind(')');
  return paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] != 'Z';
}

std::vector<long> pids_in(const fs::path& file) {
  std::vector<long> out;
  std::ifstream in(file);
  for (long pid; in >> pid;) out.push_back(pid);
  return out;
}

// A render that runs too long is killed when its task timeout passes (the
// job's task_timeout, else the farm default of farm.toml), with everything it
// started, and that attempt fails with a clear log line.
TEST_F(FarmTest, TaskTimeoutKillsARenderThatRunsTooLong) {
  const auto config = dir_ / "farm.toml";
  std::ofstream(config) << "[server]\nlease_seconds = 10\ntask_timeout = 2.0\n"
                           "[worker]\nheartbeat_seconds = 0.3\nidle_backoff_min = 0.05\n"
                           "idle_backoff_max = 0.3\nkill_grace_seconds = 0.5\n";
  const auto scene = write_scene(16, 12, 1);
  // A renderer that never finishes, and starts another process that would
  // outlive it if only the renderer were killed.
  const auto slow = dir_ / "slow-renderer.sh";
  std::ofstream(slow) << "#!/bin/sh\nsleep 60 &\necho $! >> " << (dir_ / "pids").string()
                      << "\necho $$ >> " << (dir_ / "pids").string() << "\nexec sleep 60\n";
  fs::permissions(slow, fs::perms::owner_all);
  std::ofstream(dir_ / "job.json") << nlohmann::json{
      {"format", "vesper-job/1"},
      {"scene", scene.string()},
      {"name", "own-timeout"},
      {"max_attempts", 1},
      {"task_timeout", 0.5}}.dump();
  start_server(config);
  start_worker("w1", config, {"--renderer", slow.string()});
  const auto started = std::chrono::steady_clock::now();
  const long long own = submit((dir_ / "job.json").string());
  auto j = wait_finished(own, 60);
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_EQ(j.at("counts").at("failed"), 1) << j.dump();
  EXPECT_LT(took, 20) << "a 0.5 s timeout on a 60 s render";
  // The farm default (2 s) for a job that sets none.
  const long long by_default = submit(scene.string() + " --frames 1 --max-attempts 1");
  j = wait_finished(by_default, 60);
  EXPECT_EQ(j.at("counts").at("failed"), 1) << j.dump();

  for (const auto& [job, timeout] : {std::pair{own, "0.5 s"}, std::pair{by_default, "2 s"}}) {
    const RunResult logs = farm(fmt::format("logs {}", job));
    EXPECT_NE(logs.out.find(std::string("ran longer than the task timeout of ") + timeout +
                            " and was killed"),
              std::string::npos)
        << logs.out;
  }
  EXPECT_NE(worker_log("w1").find("task timeout"), std::string::npos) << worker_log("w1");
  const std::vector<long> pids = pids_in(dir_ / "pids");
  EXPECT_EQ(pids.size(), 4u);  // two renders, each with a background sleep
  for (long pid : pids) EXPECT_FALSE(alive(pid)) << "process " << pid << " outlived its render";
}

// The server restarted for longer than the old ~1.4 s retry window (and
// longer than a lease) while a worker uploads a finished render: the worker
// keeps retrying, the restarted server renews the lease, the render is kept,
// no attempt is charged and nobody is blocklisted (threshold 1 here); the
// worker carries on with the next frame.
TEST_F(FarmTest, AServerRestartDuringAnUploadLosesNoRenderAndChargesNothing) {
  const auto config = write_config(/*lease_seconds=*/3, /*blocklist_threshold=*/1);
  // The worker retries every 1-2 s: the restarted server's reaper (every
  // 0.75 s) looks at the lease before the retry comes, so the lease must
  // have been renewed at the restart for the completion to be taken.
  const auto patient = dir_ / "patient.toml";
  std::ofstream(patient) << "[worker]\nheartbeat_seconds = 0.3\nidle_backoff_min = 2.0\n"
                            "idle_backoff_max = 2.0\n";
  const auto scene = write_scene(16, 12, 2);
  // Renders, then (the first time) holds its finished output until the test
  // has stopped the server: the worker uploads into a dead server.
  const auto held = dir_ / "held-renderer.sh";
  const std::string rendered = (dir_ / "rendered").string(), go = (dir_ / "go").string();
  // (The render's parent is this script, not the worker: VESPER_PARENT_PID says so.)
  std::ofstream(held) << "#!/bin/sh\nVESPER_PARENT_PID=$$ " << VESPER_BINARY
                      << " \"$@\" || exit $?\n"
                      << "if [ ! -e " << go << " ]; then touch " << rendered << "; while [ ! -e "
                      << go << " ]; do sleep 0.05; done; fi\n";
  fs::permissions(held, fs::perms::owner_all);
  start_server(config);
  start_worker("w1", patient, {"--renderer", held.string()});
  const long long id = submit(scene.string() + " --frames 1-2 --name restart-upload");
  for (int i = 0; i < 1200 && !fs::exists(rendered); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(fs::exists(rendered)) << worker_log("w1");
  server_->signal(SIGKILL);
  ASSERT_TRUE(server_->wait_for(5));
  std::ofstream(go) << "";
  std::this_thread::sleep_for(std::chrono::milliseconds(4000));  // > 1.4 s and > the lease
  start_server(config);                                          // same port and data dir
  const auto j = wait_finished(id, 120);
  EXPECT_EQ(j.at("counts").at("done"), 2) << j.dump();
  // One lease each (attempts count leases): nothing charged, nothing leased again.
  for (const auto& t : j.at("tasks")) EXPECT_EQ(t.at("attempts"), 1) << t.dump();
  EXPECT_TRUE(j.at("blocked_workers").empty()) << j.dump();
  const std::string log = worker_log("w1");
  EXPECT_NE(log.find("succeeded after"), std::string::npos) << log;
  EXPECT_EQ(log.find("dropped"), std::string::npos) << log;
  // The kept render is the render: bitwise a local one of the same frame.
  ASSERT_EQ(farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string())).exit_code, 0);
  ASSERT_EQ(
      run("render " + scene.string() + " -o " + (dir_ / "local.exr").string() + " --frame 1 -q")
          .exit_code,
      0);
  expect_bitwise_equal(dir_ / "frames" / "restart-upload.0001.exr", dir_ / "local.exr");
}

}  // namespace
}  // namespace vesper::test
