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
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <thread>

#include "renderer/output/exr_io.h"
#include "tests/common/chromium.h"
#include "tests/server/server_fixture.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

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
  return read_text(dir / "ramp.exr");
}

class MonitorBrowser : public ServerTest {
 protected:
  // Requests the server answered 200, not counting this call's own.
  int64_t answered_ok() {
    auto r = client().Get("/metrics", sub());
    if (!r) return -1;
    std::smatch m;
    static const std::regex ok(R"re(vesper_http_requests_total\{code="200"\} (\d+))re");
    if (!std::regex_search(r->body, m, ok)) return -1;
    return std::stoll(m[1]) - ++metrics_calls_ + 1;
  }
  // The fake worker: once the page has polled (page, script, styles, jobs,
  // workers), renders the job's tasks one after the other, a few hundred
  // milliseconds each, so the page sees them finish.
  void work_when_watched(int64_t baseline, const std::string& worker, const std::string& result,
                         int tasks) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (answered_ok() < baseline + 5 && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    for (int i = 0; i < tasks; ++i) {
      const json l = lease(worker);
      if (!l.contains("lease_id")) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(400));
      post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", result}}, wrk());
    }
  }
  int64_t metrics_calls_ = 0;
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

  const int64_t baseline = answered_ok();
  std::thread fake([&] { work_when_watched(baseline, worker, result, kTasks); });
  // Virtual time runs the page's 2 s polls without waiting for them; the
  // fetches themselves take real time, long enough for the fake worker.
  test::BrowserRun live = test::start_chromium(chromium, server_->url() + "/", dir_, "live",
                                               {"--virtual-time-budget=600000"});
  const auto code = live.process->wait_for(180);
  fake.join();
  ASSERT_EQ(code, 0) << read_text(live.log);
  EXPECT_EQ(test::console_lines(read_text(live.log)), std::vector<std::string>{});
  const std::string dom = read_text(live.dom);
  EXPECT_NE(dom.find("data-job=\"" + std::to_string(job) + "\""), std::string::npos) << dom;
  std::smatch observed;
  ASSERT_TRUE(std::regex_search(dom, observed, std::regex("data-observed=\"([^\"]*)\"")))
      << dom.substr(0, 2000);
  const std::string seen = observed[1];
  const std::string id = std::to_string(job);
  EXPECT_NE(seen.find(id + ":active:0/4"), std::string::npos) << seen;
  EXPECT_NE(seen.find(":4/4"), std::string::npos) << "the page saw the job finish: " << seen;

  // The job page, finished: thumbnails of its frames; a screenshot for a human.
  const fs::path screenshot = artifacts / "monitor-screenshot.png";
  test::BrowserRun page =
      test::start_chromium(chromium, server_->url() + "/#/jobs/" + id, dir_, "job",
                           {"--window-size=1400,1000", "--screenshot=" + screenshot.string(),
                            "--virtual-time-budget=5000"});
  ASSERT_EQ(page.process->wait_for(120), 0) << read_text(page.log);
  EXPECT_EQ(test::console_lines(read_text(page.log)), std::vector<std::string>{});
  const std::string job_dom = read_text(page.dom);
  EXPECT_NE(job_dom.find("data-view=\"job\""), std::string::npos);
  EXPECT_NE(job_dom.find("/frames/1/thumbnail"), std::string::npos);
  EXPECT_NE(job_dom.find("/frames/4/thumbnail"), std::string::npos);
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
  ASSERT_EQ(run.process->wait_for(120), 0) << read_text(run.log);
  const std::string dom = read_text(run.dom);
  EXPECT_NE(dom.find("data-view=\"login\""), std::string::npos) << dom.substr(0, 2000);
  EXPECT_NE(dom.find("<section id=\"login\">"), std::string::npos) << "shown, not hidden";
  EXPECT_NE(dom.find("<main id=\"app\" hidden"), std::string::npos);
}

}  // namespace
}  // namespace vesper
