// The monitor in a real browser (headless Chromium, Debian `chromium`)
// against a real server on 127.0.0.1 with a running job, worked by a fake
// worker in this process (the worker protocol over HTTP, a real EXR as each
// result): the page loads without a console message, shows the job, and sees
// it progress to the end without a reload (the page writes every job state it
// saw into <body data-observed>); the job page shows the finished frames'
// thumbnails; a screenshot stays in the build tree (printed). A server that
// is not read-only shows the login form. Skipped when no Chromium is installed.
#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <iostream>
#include <regex>
#include <thread>

#include "renderer/output/exr_io.h"
#include "tests/common/chromium.h"
#include "tests/common/cli_runner.h"
#include "tests/server/server_fixture.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

// A 320x180 EXR: a horizontal ramp, so the thumbnail and histogram show something.
std::string ramp_exr(const fs::path& dir) {
  LayeredImage img;
  img.width = 320;
  img.height = 180;
  img.channels = {"R", "G", "B", "A"};
  img.pixels.resize(size_t(img.width) * img.height * 4);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float v = float(x) / float(img.width - 1);
      img.at(x, y, 0) = v * v;
      img.at(x, y, 1) = v * 0.6f;
      img.at(x, y, 2) = float(y) / float(img.height);
      img.at(x, y, 3) = 1.f;
    }
  write_exr(img, dir / "ramp.exr");
  return test::slurp(dir / "ramp.exr");
}

class MonitorBrowser : public ServerTest {
 protected:
  // Answers (200) the server gave since start() to anyone but this test:
  // the browser's requests. Each request of the test is counted in own_.
  int64_t browser_answers() {
    auto r = client().Get("/metrics", sub());
    std::smatch m;
    static const std::regex ok(R"re(vesper_http_requests_total\{code="200"\} (\d+))re");
    const std::string body = r ? r->body : "";
    const int64_t n = std::regex_search(body, m, ok) ? std::stoll(m[1]) : -1;
    // This request is counted from the next reading on (counted as it is answered).
    return n - own_++;
  }
  // Waits (up to 60 s) until the browser has had `n` answers in all.
  void wait_for_browser(int64_t n) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (browser_answers() < n && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  // The fake worker, stepped by the page's polls (not by the clock, since
  // the browser runs the page in virtual time): once the page has loaded and
  // polled (page, script, styles, jobs, workers), pauses the job until the
  // page has polled twice more, resumes it, and renders its tasks.
  void work_while_watched(int64_t job_id, const std::string& worker, const std::string& result,
                          int tasks) {
    wait_for_browser(5);
    const std::string job = "/jobs/" + std::to_string(job_id);
    post_ok(job + "/pause", json::object(), sub());
    ++own_;
    wait_for_browser(browser_answers() + 4);
    post_ok(job + "/resume", json::object(), sub());
    ++own_;
    for (int i = 0; i < tasks; ++i) {
      const json l = lease(worker);
      ++own_;
      if (!l.contains("lease_id")) return;
      post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", result}}, wrk());
      ++own_;
    }
  }
  int64_t own_ = 0;
};

TEST_F(MonitorBrowser, ChromiumWatchesAJobFinishWithoutConsoleErrors) {
  const std::string chromium = test::find_chromium();
  if (chromium.empty()) GTEST_SKIP() << "no chromium on PATH (Debian package `chromium`)";
  clock_->store(double(std::time(nullptr)));  // the page shows times of day
  ServerConfig c = config();
  c.monitor_read_only = true;  // the browser has no cookie to log in with
  start(c);
  const int kTasks = 4;
  const int64_t job = submit(kTasks);
  const std::string worker = register_worker("render-node-1");
  const std::string result = put_blob(ramp_exr(dir_));
  const fs::path artifacts = fs::path(VESPER_TEST_ARTIFACT_DIR);
  fs::create_directories(artifacts);

  own_ = browser_answers() + 1;  // everything so far (this reading included) was the test's
  std::thread fake([&] { work_while_watched(job, worker, result, kTasks); });
  // Virtual time runs the page's 2 s polls back to back (600 s of them); the
  // fake worker steps along with them.
  test::BrowserRun live =
      test::start_chromium(chromium, server_->url() + "/", dir_, "live",
                           {"--virtual-time-budget=600000", "--window-size=1400,700",
                            "--screenshot=" + (artifacts / "monitor-jobs.png").string()});
  const auto code = live.process->wait_for(180);
  fake.join();
  ASSERT_EQ(code, 0) << test::slurp(live.log);
  EXPECT_EQ(test::console_lines(test::slurp(live.log)), std::vector<std::string>{});
  const std::string dom = test::slurp(live.dom);
  EXPECT_NE(dom.find("data-job=\"" + std::to_string(job) + "\""), std::string::npos) << dom;
  EXPECT_NE(dom.find("<section id=\"login\" hidden"), std::string::npos) << "read-only: no login";
  std::smatch observed;
  ASSERT_TRUE(std::regex_search(dom, observed, std::regex("data-observed=\"([^\"]*)\"")))
      << dom.substr(0, 2000);
  const std::string seen = observed[1];
  const std::string id = std::to_string(job);
  // The job as it was, then paused: seen live, without a reload.
  EXPECT_NE(seen.find(id + ":active:0/4"), std::string::npos) << seen;
  EXPECT_NE(seen.find(id + ":paused:0/4"), std::string::npos) << seen;
  std::cout << "the page saw: " << seen << std::endl;

  // The job page, finished: thumbnails of its frames, frame 2's histogram; a
  // screenshot for a human.
  const fs::path screenshot = artifacts / "monitor-screenshot.png";
  test::BrowserRun page =
      test::start_chromium(chromium, server_->url() + "/#/jobs/" + id + "/frames/2", dir_, "job",
                           {"--window-size=1400,1000", "--screenshot=" + screenshot.string(),
                            "--virtual-time-budget=5000"});
  ASSERT_EQ(page.process->wait_for(120), 0) << test::slurp(page.log);
  EXPECT_EQ(test::console_lines(test::slurp(page.log)), std::vector<std::string>{});
  const std::string job_dom = test::slurp(page.dom);
  EXPECT_NE(job_dom.find("data-view=\"job\""), std::string::npos);
  EXPECT_NE(job_dom.find("4/4 · 100 %"), std::string::npos) << "finished";
  EXPECT_NE(job_dom.find("/frames/1/thumbnail"), std::string::npos);
  EXPECT_NE(job_dom.find("/frames/4/thumbnail"), std::string::npos);
  EXPECT_NE(job_dom.find(">render-node-1<"), std::string::npos) << "tasks name their worker";
  // The histogram of frame 2, drawn: its pixel count lands on the canvas.
  EXPECT_NE(job_dom.find("data-count=\"57600\""), std::string::npos)
      << "320 x 180 pixels: " << job_dom;
  ASSERT_TRUE(fs::is_regular_file(screenshot));
  EXPECT_GT(fs::file_size(screenshot), 10000u);
  std::cout << "screenshot: " << screenshot.string() << std::endl;
}

TEST_F(MonitorBrowser, WithoutASessionThePageShowsTheLoginForm) {
  const std::string chromium = test::find_chromium();
  if (chromium.empty()) GTEST_SKIP() << "no chromium on PATH (Debian package `chromium`)";
  start();
  test::BrowserRun run = test::start_chromium(chromium, server_->url() + "/", dir_, "login",
                                              {"--virtual-time-budget=5000"});
  ASSERT_EQ(run.process->wait_for(120), 0) << test::slurp(run.log);
  const std::string dom = test::slurp(run.dom);
  EXPECT_NE(dom.find("data-view=\"login\""), std::string::npos) << dom.substr(0, 2000);
  EXPECT_NE(dom.find("<section id=\"login\">"), std::string::npos) << "shown, not hidden";
  EXPECT_NE(dom.find("<main id=\"app\" hidden"), std::string::npos);
}

}  // namespace
}  // namespace vesper
