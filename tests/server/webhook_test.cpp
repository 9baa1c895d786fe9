// The job webhook ([server] webhook_url, server/job_webhook.h): a job that
// ends done, failed or canceled is announced once with a POST of JSON to a
// listener on 127.0.0.1 (httplib::Server), retried when the listener fails,
// and not announced again after a restart.
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

// An HTTP listener on 127.0.0.1 that records every POST /hook body; the
// first `failures` requests are answered 500.
class HookListener {
 public:
  explicit HookListener(int failures) : failures_(failures) {
    server_.Post("/hook", [this](const httplib::Request& req, httplib::Response& res) {
      std::lock_guard lock(mutex_);
      ++requests_;
      if (requests_ <= failures_) {
        res.status = 500;
        return;
      }
      bodies_.push_back(nlohmann::json::parse(req.body));
      res.set_content("{}", "application/json");
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
  }
  ~HookListener() {
    server_.stop();
    thread_.join();
  }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/hook"; }
  int requests() {
    std::lock_guard lock(mutex_);
    return requests_;
  }
  std::vector<nlohmann::json> bodies() {
    std::lock_guard lock(mutex_);
    return bodies_;
  }
  // The announcements once there are `n` (after at most 20 s).
  std::vector<nlohmann::json> wait_for(size_t n) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (bodies().size() < n && std::chrono::steady_clock::now() < end)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return bodies();
  }

 private:
  httplib::Server server_;
  std::thread thread_;
  int port_ = 0, failures_ = 0, requests_ = 0;
  std::mutex mutex_;
  std::vector<nlohmann::json> bodies_;
};

using WebhookTest = ServerTest;

TEST_F(WebhookTest, JobsThatEndAreAnnouncedOnceEach) {
  HookListener hook(1);  // the first POST fails: retried
  ServerConfig c = config();
  c.webhook_url = hook.url();
  start(c);
  const std::string w = register_worker("w");
  const int64_t done = submit(1);
  advance(5);
  const json l = lease(w);
  advance(2);
  post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", put_blob("frame")}}, wrk());
  auto got = hook.wait_for(1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(hook.requests(), 2) << "one failure, one retry";
  EXPECT_EQ(got[0].at("id"), done);
  EXPECT_EQ(got[0].at("name"), "test");
  EXPECT_EQ(got[0].at("state"), "done");
  EXPECT_EQ(got[0].at("submitted"), 1000);
  EXPECT_EQ(got[0].at("started"), 1005);
  EXPECT_EQ(got[0].at("finished"), 1007);
  EXPECT_EQ(got[0].at("frames"), 1);
  EXPECT_EQ(got[0].at("failed_tasks"), 0);

  const int64_t failed = submit(2, 8, 0, 1);
  for (int i = 0; i < 2; ++i)
    post_ok("/fail", {{"lease_id", lease(w).at("lease_id")}, {"log", "crash"}}, wrk());
  const int64_t canceled = submit(3);
  post_ok("/jobs/" + std::to_string(canceled) + "/cancel", json::object(), sub());
  got = hook.wait_for(3);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[1].at("id"), failed);
  EXPECT_EQ(got[1].at("state"), "failed");
  EXPECT_EQ(got[1].at("frames"), 2);
  EXPECT_EQ(got[1].at("failed_tasks"), 2);
  EXPECT_EQ(got[2].at("id"), canceled);
  EXPECT_EQ(got[2].at("state"), "canceled");
  EXPECT_FALSE(got[2].contains("started"));

  // A restart announces nothing again; a retried job that ends again is.
  start(c);
  post_ok("/jobs/" + std::to_string(failed) + "/retry-failed", json::object(), sub());
  for (int i = 0; i < 2; ++i)
    post_ok("/fail", {{"lease_id", lease(w).at("lease_id")}, {"log", "crash"}}, wrk());
  got = hook.wait_for(4);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got[3].at("id"), failed);
  std::this_thread::sleep_for(std::chrono::seconds(1));  // nothing more comes
  EXPECT_EQ(hook.bodies().size(), 4u);
}

TEST_F(WebhookTest, AListenerThatNeverAnswersIsGivenUpOnAndTheServerGoesOn) {
  HookListener hook(1000);
  ServerConfig c = config();
  c.webhook_url = hook.url();
  start(c);
  const int64_t job = submit(1);
  post_ok("/jobs/" + std::to_string(job) + "/cancel", json::object(), sub());
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (hook.requests() < 3 && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(hook.requests(), 3) << "three attempts";
  std::this_thread::sleep_for(std::chrono::seconds(1));  // and no more
  EXPECT_EQ(hook.requests(), 3);
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(job)).at("state"), "canceled");
}

}  // namespace
}  // namespace vesper
