// The job lifecycle end to end, with real `vesper server` and `vesper
// worker` processes on 127.0.0.1 (docs/farm.md, "Job lifecycle"): cancel
// kills the running render at the next heartbeat (checked by its PID), jobs
// end done / failed / canceled with their times in `vesper status`, every
// task keeps a log tail (`vesper logs`), and a resubmitted job is done at
// submit even behind a busy job of higher priority.
#include <fmt/format.h>
#include <signal.h>

#include <algorithm>
#include <cstdio>

#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

// The live (not zombie) children of `parent` whose command line has `text`.
std::vector<pid_t> children_with(pid_t parent, const std::string& text) {
  std::vector<pid_t> out;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = slurp(entry.path() / "stat");
    const size_t paren = stat.rfind(')');
    if (paren == std::string::npos || paren + 4 >= stat.size()) continue;
    // After "(comm) ": the state, then the parent's pid.
    const char state = stat[paren + 2];
    const long ppid = std::atol(stat.c_str() + paren + 4);
    std::string cmdline = slurp(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (ppid == parent && state != 'Z' && cmdline.find(text) != std::string::npos)
      out.push_back(pid_t(std::stol(pid)));
  }
  return out;
}

// Whether `pid` is a live process (a zombie is not).
bool alive(pid_t pid) {
  const std::string stat = slurp(fmt::format("/proc/{}/stat", pid));
  const size_t paren = stat.rfind(')');
  return paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] != 'Z';
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

bool ended(const nlohmann::json& j) {
  const std::string s = j.at("state");
  return s == "done" || s == "failed" || s == "canceled";
}

// The farm's settings with a heartbeat of `heartbeat` seconds.
std::filesystem::path config_with_heartbeat(const std::filesystem::path& dir, double heartbeat,
                                            double grace) {
  const auto p = dir / "farm-heartbeat.toml";
  std::ofstream(p) << "[server]\nlease_seconds = 10\n[worker]\nheartbeat_seconds = " << heartbeat
                   << "\nidle_backoff_min = 0.05\nidle_backoff_max = 0.3\nkill_grace_seconds = "
                   << grace << "\n";
  return p;
}

// Cancel reaches a running render at the worker's next heartbeat: the
// render's process (found by PID as the worker's child) is gone within one
// heartbeat interval plus the kill grace, long before it would have ended.
TEST_F(FarmTest, CancelKillsTheRunningRenderWithinOneHeartbeat) {
  const double heartbeat = 0.5, grace = 0.5;
  const auto config = config_with_heartbeat(dir_, heartbeat, grace);
  const auto scene = write_scene(64, 48, 1 << 20);  // minutes of rendering
  start_server(config);
  auto& worker = start_worker("w1", config);
  const long long id = submit(scene.string() + " --frames 1 --name long");
  std::vector<pid_t> render;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (render.empty() && std::chrono::steady_clock::now() < deadline) {
    render = children_with(worker.pid(), " render ");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(render.size(), 1u) << worker_log("w1");
  std::this_thread::sleep_for(std::chrono::duration<double>(2 * heartbeat));  // well under way
  ASSERT_TRUE(alive(render[0]));

  // Timed from the cancel's answer (the API's, not a `vesper cancel`
  // process's: its start-up is no part of the protocol).
  httplib::Client http("127.0.0.1", port_);
  http.set_bearer_token_auth(submitter_);
  const auto answer =
      http.Post(fmt::format("/api/v1/jobs/{}/cancel", id), "{}", "application/json");
  const auto canceled_at = std::chrono::steady_clock::now();
  ASSERT_TRUE(answer);
  ASSERT_EQ(answer->status, 200) << answer->body;
  while (alive(render[0]) && seconds_since(canceled_at) < 30)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const double gone_after = seconds_since(canceled_at);
  EXPECT_FALSE(alive(render[0])) << worker_log("w1");
  // One heartbeat interval plus the kill grace, with half a second for the
  // HTTP round trip and the worker's reaping on a loaded machine.
  EXPECT_LT(gone_after, heartbeat + grace + 0.5) << worker_log("w1");
  std::printf("render gone %.3f s after the cancel (heartbeat %.1f s, grace %.1f s)\n", gone_after,
              heartbeat, grace);
  EXPECT_NE(worker_log("w1").find("the server says stop; killing the render"), std::string::npos)
      << worker_log("w1");
  const auto j = job(id);
  EXPECT_EQ(j.at("state"), "canceled") << j.dump();
  EXPECT_TRUE(j.contains("finished")) << j.dump();
  EXPECT_FALSE(worker.wait_for(0).has_value()) << "the worker goes on";
}

// Jobs end and say what happened: `vesper status` lists state and times,
// one job's tasks show attempts, worker and duration; every task keeps the
// tail of its render's log, which `vesper logs` prints.
TEST_F(FarmTest, StatusAndLogsShowHowJobsEnded) {
  const auto config = write_config(10);
  const auto scene = write_scene(32, 24, 4);
  start_server(config);
  start_worker("w1", config);
  const long long id = submit(scene.string() + " --frames 1-2 --name ok");
  const auto j = wait_finished(id, 120);
  ASSERT_EQ(j.at("state"), "done") << j.dump();
  EXPECT_GE(j.at("started").get<double>(), j.at("submitted").get<double>());
  EXPECT_GE(j.at("finished").get<double>(), j.at("started").get<double>());
  EXPECT_FALSE(j.contains("eta"));
  for (const auto& t : j.at("tasks")) {
    EXPECT_EQ(t.at("attempts"), 1) << t.dump();
    EXPECT_TRUE(t.at("has_log").get<bool>()) << t.dump();
    EXPECT_GE(t.at("duration").get<double>(), 0) << t.dump();
    EXPECT_FALSE(t.at("worker").get<std::string>().empty());
  }

  const RunResult list = farm("status");
  ASSERT_EQ(list.exit_code, 0) << list.err;
  for (const char* column : {"state", "submitted", "started", "finished", "duration", "eta"})
    EXPECT_NE(list.out.find(column), std::string::npos) << list.out;
  EXPECT_NE(list.out.find(" done "), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("2/2"), std::string::npos) << list.out;
  const RunResult one = farm(fmt::format("status {}", id));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("submitted "), std::string::npos) << one.out;
  EXPECT_NE(one.out.find(", took "), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("duration"), std::string::npos) << one.out;

  const RunResult logs = farm(fmt::format("logs {}", id));
  ASSERT_EQ(logs.exit_code, 0) << logs.err;
  const std::string first = j.at("tasks").at(0).at("id").dump();
  EXPECT_NE(logs.out.find("=== task " + first + " (frame 1"), std::string::npos) << logs.out;
  EXPECT_NE(logs.out.find("done, attempts: 1 ==="), std::string::npos) << logs.out;
  const RunResult one_log = farm(fmt::format("logs {} --task {}", id, first));
  ASSERT_EQ(one_log.exit_code, 0) << one_log.err;
  EXPECT_FALSE(one_log.out.empty());
  EXPECT_EQ(one_log.out.find("=== task"), std::string::npos) << one_log.out;
  EXPECT_NE(logs.out.find(one_log.out), std::string::npos) << "the same tail";
  const RunResult no_task = farm(fmt::format("logs {} --task 999999", id));
  EXPECT_NE(no_task.exit_code, 0);
  EXPECT_NE(no_task.err.find("no task 999999"), std::string::npos) << no_task.err;
}

// A job whose frames were all rendered before is done at submit, even while
// a job of higher priority keeps the only worker busy: nothing is rendered.
TEST_F(FarmTest, AResubmittedJobIsDoneAtOnceBehindABusyJob) {
  const auto config = write_config(10);
  const auto scene = write_scene(32, 24, 4);
  start_server(config);
  start_worker("w1", config);
  const long long first = submit(scene.string() + " --frames 1-2 --name first");
  ASSERT_EQ(wait_finished(first, 120).at("state"), "done");
  const long long busy =
      submit(scene.string() + " --frames 1 --spp 1048576 --priority 90 --name busy");
  wait_job(busy, 60, [](const nlohmann::json& j) { return j.at("counts").at("leased") == 1; });

  const long long again = submit(scene.string() + " --frames 1-2 --name again");
  const auto j = wait_job(again, 10, ended);
  EXPECT_EQ(j.at("state"), "done") << j.dump();
  for (const auto& t : j.at("tasks")) {
    EXPECT_TRUE(t.contains("reused_from")) << t.dump();
    EXPECT_EQ(t.at("attempts"), 0) << t.dump();
  }
  EXPECT_EQ(job(busy).at("state"), "active");
  EXPECT_EQ(std::count_if(j.at("tasks").begin(), j.at("tasks").end(),
                          [](const nlohmann::json& t) { return t.at("state") == "done"; }),
            2);
  const RunResult fetched = farm(fmt::format("fetch {} -o {}", again, (dir_ / "frames").string()));
  EXPECT_EQ(fetched.exit_code, 0) << fetched.err;
  ASSERT_EQ(farm(fmt::format("cancel {}", busy)).exit_code, 0);
}

}  // namespace
}  // namespace vesper::test
