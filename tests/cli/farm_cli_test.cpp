// The farm end to end: real `vesper server` and `vesper worker` processes on
// 127.0.0.1, jobs submitted with `vesper submit`, frames fetched with `vesper
// fetch` and compared bit for bit with direct `vesper render` runs. Processes
// are killed with SIGKILL / stopped with SIGSTOP to check nothing is lost.
#include <fmt/format.h>

#include <algorithm>

#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

// Whether a live (not zombie) process has `text` in its command line.
bool process_running_with(const std::string& text) {
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = slurp(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    const std::string stat = slurp(entry.path() / "stat");
    const size_t paren = stat.rfind(')');
    const bool zombie =
        paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] == 'Z';
    if (!zombie && cmdline.find(text) != std::string::npos) return true;
  }
  return false;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_F(FarmTest, SixFramesOnTwoWorkersEqualLocalRenders) {
  const auto config = write_config(10);
  const auto scene = write_scene(48, 36, 8);
  start_server(config);
  start_worker("w1", config);
  start_worker("w2", config);
  const long long id = submit(scene.string() + " --frames 1-6 --name six");
  const auto j = wait_finished(id, 120);
  ASSERT_EQ(j.at("counts").at("done"), 6) << j.dump();

  const RunResult f = farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string()));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  for (int frame = 1; frame <= 6; ++frame) {
    const auto local = dir_ / fmt::format("local.{}.exr", frame);
    const RunResult r =
        run(fmt::format("render {} -o {} --frame {} -q", scene.string(), local.string(), frame));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_bitwise_equal(dir_ / "frames" / fmt::format("six.{:04d}.exr", frame), local);
  }
  // Frames are decorrelated: frame 1 and frame 2 are different renders.
  const LayeredImage a = read_exr(dir_ / "frames/six.0001.exr"),
                     b = read_exr(dir_ / "frames/six.0002.exr");
  EXPECT_NE(a.pixels, b.pixels);
}

TEST_F(FarmTest, FrameSplitIntoFourTasksMergesToTheSingleRender) {
  const auto config = write_config(10);
  const auto scene = write_scene(40, 30, 20);
  start_server(config);
  start_worker("w1", config);
  start_worker("w2", config);
  // 20 samples in tasks of 6: [0,6) [6,12) [12,18) [18,20).
  const long long id = submit(scene.string() + " --frames 7 --split 6 --name split");
  const auto j = wait_finished(id, 120);
  ASSERT_EQ(j.at("counts").at("done"), 4) << j.dump();
  const RunResult f = farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string()));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const auto local = dir_ / "local.exr";
  ASSERT_EQ(
      run(fmt::format("render {} -o {} --frame 7 -q", scene.string(), local.string())).exit_code,
      0);
  expect_bitwise_equal(dir_ / "frames/split.0007.exr", local);
}

// A worker killed while it renders: its lease expires, the other worker
// renders the task, the job completes with every frame.
TEST_F(FarmTest, KilledWorkerLosesNoWork) {
  const auto config = write_config(2);
  const auto scene = write_scene(64, 48, 1600);  // ~6 s on one thread
  start_server(config);
  // A quiet render (-q): it writes nothing to the dead worker's stderr pipe,
  // so only the parent-death signal can end it (a chatty one would also die
  // of SIGPIPE at its next progress line). exec keeps the worker its parent.
  const auto quiet = dir_ / "quiet-renderer.sh";
  std::ofstream(quiet) << "#!/bin/sh\nexec " << VESPER_BINARY << " \"$@\" -q\n";
  std::filesystem::permissions(quiet, std::filesystem::perms::owner_all);
  auto& doomed = start_worker("doomed", config, {"--renderer", quiet.string()});
  const long long id = submit(scene.string() + " --frames 1 --name kill");
  wait_job(id, 60, [](const nlohmann::json& j) { return j.at("counts").at("leased") == 1; });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // mid-render
  doomed.signal(SIGKILL);
  ASSERT_TRUE(doomed.wait_for(5));
  // Its render (a child in its own process group, ~5 s from its end) dies
  // with it: gone within 2 s. Not 1 s: on a loaded machine a render killed
  // while still loading its ~260 shared libraries only sees its parent's
  // death once it reaches main (seen at load average 12).
  const std::string marker = (dir_ / "cache-doomed").string();
  bool orphan = true;
  for (int i = 0; i < 40 && orphan; ++i, std::this_thread::sleep_for(std::chrono::milliseconds(50)))
    orphan = process_running_with(marker);
  EXPECT_FALSE(orphan) << "the killed worker's render is still running";
  start_worker("survivor", config);
  const auto j = wait_finished(id, 180);
  EXPECT_EQ(j.at("counts").at("done"), 1) << j.dump();
  int retried = 0;
  for (const auto& t : j.at("tasks")) retried += t.at("attempts").get<int>() > 0;
  EXPECT_GE(retried, 1) << "the killed worker's lease should count as a failed attempt";
  const RunResult f = farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string()));
  EXPECT_EQ(f.exit_code, 0) << f.err;
  EXPECT_EQ(count(f.out, ".exr"), 1) << f.out;
}

// A worker frozen (SIGSTOP) past its lease comes back after the task was
// rendered by another worker: its upload is refused and the committed result
// stays the other worker's.
TEST_F(FarmTest, LateCompletionOfAnExpiredLeaseIsRefused) {
  const auto config = write_config(1.5);
  const auto scene = write_scene(64, 48, 300);
  start_server(config);
  auto& sleeper = start_worker("sleeper", config);
  const long long id = submit(scene.string() + " --frames 1 --name late");
  wait_job(id, 60, [](const nlohmann::json& j) { return j.at("counts").at("leased") == 1; });
  sleeper.signal(SIGSTOP);
  start_worker("other", config);
  const auto j = wait_finished(id, 180);
  ASSERT_EQ(j.at("counts").at("done"), 1);
  const std::string result = j.at("tasks").at(0).at("result");
  sleeper.signal(SIGCONT);
  // The sleeper's render (its child kept running) ends; its lease is stale.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (worker_log("sleeper").find("stale") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_NE(worker_log("sleeper").find("stale"), std::string::npos) << worker_log("sleeper");
  const auto after = job(id);
  EXPECT_EQ(after.at("counts").at("done"), 1);
  EXPECT_EQ(after.at("tasks").at(0).at("result"), result) << "a stale upload replaced the result";
}

// The server killed mid-job and restarted on the same data dir and port:
// committed frames stay committed, the job completes.
TEST_F(FarmTest, KilledServerRestartsAndTheJobCompletes) {
  const auto config = write_config(3);
  const auto scene = write_scene(48, 36, 100);
  start_server(config);
  start_worker("w1", config);
  const long long id = submit(scene.string() + " --frames 1-4 --name restart");
  const auto before =
      wait_job(id, 120, [](const nlohmann::json& j) { return j.at("counts").at("done") >= 1; });
  std::map<long long, std::string> committed;
  for (const auto& t : before.at("tasks"))
    if (t.at("state") == "done") committed[t.at("id")] = t.at("result");
  server_->signal(SIGKILL);
  ASSERT_TRUE(server_->wait_for(5));
  start_server(config);  // same port
  const auto j = wait_finished(id, 180);
  EXPECT_EQ(j.at("counts").at("done"), 4) << j.dump();
  for (const auto& t : j.at("tasks")) {
    if (committed.count(t.at("id"))) {
      EXPECT_EQ(t.at("result"), committed[t.at("id")]);
    }
  }
}

// A renderer that crashes on frame 3 fails that task after max attempts (with
// its log); the rest of the job completes; a worker whose renderer always
// crashes is blocklisted for the job after `blocklist_threshold` failures.
TEST_F(FarmTest, CrashingRenderFailsItsTaskAndBlocklistsTheBrokenWorker) {
  const auto config = write_config(10, 2);
  const auto scene = write_scene(32, 24, 4);
  const auto broken = dir_ / "broken-renderer.sh";
  std::ofstream(broken) << "#!/bin/sh\necho 'renderer: simulated crash' >&2\nkill -SEGV $$\n";
  const auto flaky = dir_ / "crash-on-frame-3.sh";
  std::ofstream(flaky) << "#!/bin/sh\ncase \" $* \" in *\" --frame 3 \"*) echo 'frame 3 crashes' "
                          ">&2; kill -SEGV $$;; esac\nexec "
                       << VESPER_BINARY << " \"$@\"\n";
  std::filesystem::permissions(broken, std::filesystem::perms::owner_all);
  std::filesystem::permissions(flaky, std::filesystem::perms::owner_all);
  start_server(config);
  const long long id = submit(scene.string() + " --frames 1-4 --max-attempts 3 --name crash");
  // The broken worker alone first: it fails two tasks, then is blocked.
  start_worker("broken", config, {"--renderer", broken.string()});
  wait_job(id, 60, [](const nlohmann::json& j) {
    int attempts = 0;
    for (const auto& t : j.at("tasks")) attempts += t.at("attempts").get<int>();
    return attempts >= 2;
  });
  start_worker("flaky", config, {"--renderer", flaky.string()});
  const auto j = wait_finished(id, 120);
  EXPECT_EQ(j.at("counts").at("done"), 3) << j.dump();
  EXPECT_EQ(j.at("counts").at("failed"), 1) << j.dump();
  for (const auto& t : j.at("tasks")) {
    if (t.at("frame") != 3) continue;
    EXPECT_EQ(t.at("state"), "failed");
    EXPECT_EQ(t.at("attempts"), 3);
    EXPECT_TRUE(t.at("has_log").get<bool>());
  }
  const RunResult logs = farm(fmt::format("logs {}", id));
  EXPECT_EQ(logs.exit_code, 0) << logs.err;
  EXPECT_NE(logs.out.find("frame 3 crashes"), std::string::npos) << logs.out;
  EXPECT_NE(logs.out.find("signal"), std::string::npos) << logs.out;
  // Blocked after its second failed task: the broken worker never got a third.
  EXPECT_EQ(count(worker_log("broken"), "render failed"), 2) << worker_log("broken");
  httplib::Client c("127.0.0.1", port_);
  c.set_bearer_token_auth(submitter_);
  const auto workers = nlohmann::json::parse(c.Get("/api/v1/workers")->body);
  std::map<std::string, std::string> id_of;
  for (const auto& w : workers.at("workers")) id_of[w.at("name")] = w.at("worker_id");
  EXPECT_EQ(j.at("blocked_workers"), nlohmann::json::array({id_of["broken"]})) << j.dump();
  const RunResult status = farm(fmt::format("status {}", id));
  EXPECT_EQ(status.exit_code, 0);
  EXPECT_NE(status.out.find("1 failed"), std::string::npos) << status.out;
}

// The same scene submitted again: its tasks are done at once with the first
// job's results (same inputs, same renderer build), nothing is rendered twice.
TEST_F(FarmTest, ResubmittedSceneIsNotRenderedAgain) {
  const auto config = write_config(10);
  const auto scene = write_scene(32, 24, 4);
  start_server(config);
  start_worker("w1", config);
  const long long first = submit(scene.string() + " --frames 1-2 --name first");
  ASSERT_EQ(wait_finished(first, 60).at("counts").at("done"), 2);
  const long long second = submit(scene.string() + " --frames 1-3 --name second");
  const auto j = wait_finished(second, 60);
  ASSERT_EQ(j.at("counts").at("done"), 3) << j.dump();
  EXPECT_EQ(count(worker_log("w1"), "): leased"), 3) << worker_log("w1");
  const auto f = job(first);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(j.at("tasks").at(i).at("reused_from"), f.at("tasks").at(i).at("id"));
    EXPECT_EQ(j.at("tasks").at(i).at("result"), f.at("tasks").at(i).at("result"));
  }
  EXPECT_FALSE(j.at("tasks").at(2).contains("reused_from"));
  const RunResult fetched = farm(fmt::format("fetch {} -o {}", second, (dir_ / "frames").string()));
  EXPECT_EQ(fetched.exit_code, 0) << fetched.err;
  EXPECT_EQ(count(fetched.out, ".exr"), 3) << fetched.out;
}

// Pause stops leasing and lets the running render finish (its result is
// kept, not rendered again); resume finishes the job; `vesper workers` and
// `vesper status` name the workers.
TEST_F(FarmTest, PauseLetsTheRunningRenderFinishAndResumeEndsTheJob) {
  const auto config = write_config(10);
  const auto scene = write_scene(48, 36, 800);
  start_server(config);
  start_worker("w1", config);
  const long long id = submit(scene.string() + " --frames 1-2 --name pause");
  wait_job(id, 60, [](const nlohmann::json& j) { return j.at("counts").at("leased") == 1; });
  const RunResult p = farm(fmt::format("pause {}", id));
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const auto paused = wait_job(id, 60, [](const nlohmann::json& j) {
    return j.at("counts").at("done") == 1 && j.at("counts").at("paused") == 1;
  });
  EXPECT_EQ(paused.at("state"), "paused") << paused.dump();
  EXPECT_EQ(paused.at("tasks").at(0).at("attempts"), 1) << paused.dump();
  EXPECT_EQ(count(worker_log("w1"), "killing the render"), 0) << worker_log("w1");
  const RunResult w = farm("workers");
  EXPECT_EQ(w.exit_code, 0) << w.err;
  EXPECT_NE(w.out.find("w1"), std::string::npos) << w.out;
  ASSERT_EQ(farm(fmt::format("resume {}", id)).exit_code, 0);
  const auto done = wait_finished(id, 120);
  EXPECT_EQ(done.at("state"), "done") << done.dump();
  EXPECT_EQ(done.at("counts").at("done"), 2);
  EXPECT_EQ(count(worker_log("w1"), "): leased"), 2) << worker_log("w1");
  const RunResult st = farm(fmt::format("status {}", id));
  EXPECT_EQ(st.exit_code, 0) << st.err;
  EXPECT_EQ(count(st.out, " w1"), 2) << st.out;
  EXPECT_NE(farm("pause 999").err.find("no job 999"), std::string::npos);
}

// When every worker is blocklisted for a job, `submit --wait` says so and
// returns instead of waiting forever for tasks nobody may take.
TEST_F(FarmTest, WaitStopsWhenEveryWorkerIsBlocked) {
  const auto config = write_config(10, 2);
  const auto scene = write_scene(16, 12, 1);
  const auto broken = dir_ / "broken-renderer.sh";
  std::ofstream(broken) << "#!/bin/sh\nexit 7\n";
  std::filesystem::permissions(broken, std::filesystem::perms::owner_all);
  start_server(config);
  start_worker("only", config, {"--renderer", broken.string()});
  const RunResult r = farm("submit " + scene.string() + " --frames 1-5 --max-attempts 5 --wait");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("every registered worker is blocklisted"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("5 queued tasks"), std::string::npos) << r.err;
}

TEST_F(FarmTest, SubmitErrorsNameTheProblem) {
  const auto config = write_config(10);
  const auto scene = write_scene(16, 16, 1);
  start_server(config);
  const RunResult bad_token =
      run("submit " + scene.string() + " --server " + url_ + " --token nope");
  EXPECT_EQ(bad_token.exit_code, 1);
  EXPECT_NE(bad_token.err.find("401"), std::string::npos) << bad_token.err;

  const auto job_file = dir_ / "job.json";
  std::ofstream(job_file)
      << R"({"format": "vesper-job/1", "scene": "scene/scene.json", "spp": -3})";
  const RunResult bad_job = farm("submit " + job_file.string());
  EXPECT_EQ(bad_job.exit_code, 2);
  EXPECT_NE(bad_job.err.find("job.json: /spp: expected an integer"), std::string::npos)
      << bad_job.err;

  const RunResult bad_frames = farm("submit " + scene.string() + " --frames 5-1");
  EXPECT_NE(bad_frames.exit_code, 0);
  EXPECT_NE(bad_frames.err.find("5-1"), std::string::npos) << bad_frames.err;

  const RunResult dry = farm("submit " + scene.string() + " --frames 1-10x3 --dry-run");
  EXPECT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_NE(dry.err.find("4 tasks"), std::string::npos) << dry.err;
  const RunResult status = farm("status");
  EXPECT_NE(status.out.find("no jobs"), std::string::npos) << status.out;
}

TEST_F(FarmTest, UpRendersFetchesAndComposites) {
  const auto scene = write_scene(32, 24, 4);
  std::ofstream(scene.parent_path() / "comp.json") << R"({
    "format": "vesper-comp/1", "inputs": {"frame": "unused.exr"},
    "layers": [{"layer": "beauty"}],
    "outputs": {"image": "x.png", "histogram_plot": "x.hist.png"}})";
  const RunResult r =
      run(fmt::format("up --scene {} --frames 1-2 --workers 2 --data-dir {} -o {}", scene.string(),
                      (dir_ / "farm").string(), (dir_ / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out/scene.0001.exr")) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out/scene.0002.exr")) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out/scene.0002.comp.png")) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out/scene.0002.comp.hist.png")) << r.out;
}

}  // namespace
}  // namespace vesper::test
