#pragma once
// A farm of real processes on 127.0.0.1 for end-to-end tests: `vesper server`
// and `vesper worker` processes started from the built binary, a small scene
// with a mesh asset, and helpers to submit, poll and compare frames.
#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "renderer/output/exr_io.h"
#include "tests/common/background_process.h"
#include "tests/common/cli_runner.h"

namespace vesper::test {

class FarmTest : public CliTest {
 protected:
  FarmTest() : CliTest("") {}

  void TearDown() override {
    workers_.clear();
    server_.reset();
    CliTest::TearDown();
  }

  // The farm's settings for tests: short leases so a dead worker's task comes
  // back within seconds.
  std::filesystem::path write_config(double lease_seconds = 2, int blocklist_threshold = 3) {
    const auto p = dir_ / "farm.toml";
    std::ofstream(p) << "[server]\nlease_seconds = " << lease_seconds
                     << "\nblocklist_threshold = " << blocklist_threshold
                     << "\n[worker]\nheartbeat_seconds = 0.3\nidle_backoff_min = 0.05\n"
                        "idle_backoff_max = 0.3\nkill_grace_seconds = 0.5\n";
    return p;
  }

  // The Cornell box (with its cube.obj mesh asset) at a small size.
  std::filesystem::path write_scene(int width, int height, int spp) {
    std::ifstream in(std::string(VESPER_SOURCE_DIR) + "/scenes/cornell/scene.json");
    auto doc = nlohmann::json::parse(in);
    doc["film"]["width"] = width;
    doc["film"]["height"] = height;
    doc["render"]["spp"] = spp;
    for (auto& s : doc["shapes"])
      if (s.contains("file"))
        s["file"] = std::string(VESPER_SOURCE_DIR) + "/scenes/cornell/cube.obj";
    const auto p = dir_ / "scene" / "scene.json";
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p) << doc.dump(2);
    return p;
  }

  // Starts `vesper server` (port 0 = a free one the first time; a restart
  // reuses the port so workers find it again) and waits for its URL.
  void start_server(const std::filesystem::path& config) {
    const int n = ++server_starts_;
    std::vector<std::string> argv = {VESPER_BINARY, "server",
                                     "--config",    config.string(),
                                     "--data-dir",  (dir_ / "data").string(),
                                     "--port",      std::to_string(port_)};
    const auto out = dir_ / ("server" + std::to_string(n) + ".out");
    server_ = std::make_unique<BackgroundProcess>(argv, out,
                                                  dir_ / ("server" + std::to_string(n) + ".log"));
    for (int i = 0; i < 500 && slurp(out).find('\n') == std::string::npos; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    url_ = slurp(out);
    ASSERT_FALSE(url_.empty()) << slurp(dir_ / ("server" + std::to_string(n) + ".log"));
    url_.pop_back();
    port_ = std::stoi(url_.substr(url_.rfind(':') + 1));
    const auto tokens = nlohmann::json::parse(slurp(dir_ / "data" / "tokens.json"));
    submitter_ = tokens.at("submitter");
    worker_token_ = tokens.at("worker");
  }

  BackgroundProcess& start_worker(const std::string& name, const std::filesystem::path& config,
                                  const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv = {
        VESPER_BINARY, "worker", "--config",    config.string(),
        "--server",    url_,     "--token",     worker_token_,
        "--name",      name,     "--cache-dir", (dir_ / ("cache-" + name)).string(),
        "--threads",   "1"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    workers_[name] =
        std::make_unique<BackgroundProcess>(argv, dir_ / (name + ".out"), dir_ / (name + ".log"));
    return *workers_[name];
  }

  std::string worker_log(const std::string& name) { return slurp(dir_ / (name + ".log")); }

  // `vesper <args>` against this farm (adds --server and --token).
  RunResult farm(const std::string& args) {
    return run(args + " --server " + url_ + " --token " + submitter_);
  }

  long long submit(const std::string& args) {
    const RunResult r = farm("submit " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 ? std::stoll(r.out) : -1;
  }

  nlohmann::json job(long long id) {
    httplib::Client c("127.0.0.1", port_);
    c.set_bearer_token_auth(submitter_);
    auto res = c.Get("/api/v1/jobs/" + std::to_string(id));
    if (!res || res->status != 200) return nlohmann::json();
    return nlohmann::json::parse(res->body);
  }

  // Polls until `pred(job)` holds; fails the test after `seconds`.
  nlohmann::json wait_job(long long id, double seconds,
                          const std::function<bool(const nlohmann::json&)>& pred) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    nlohmann::json j;
    while (std::chrono::steady_clock::now() < end) {
      j = job(id);
      if (!j.is_null() && pred(j)) return j;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ADD_FAILURE() << "job " << id << " did not reach the expected state in " << seconds
                  << " s; last: " << j.dump();
    return j;
  }
  // Until the job ended: done, failed or canceled.
  nlohmann::json wait_finished(long long id, double seconds) {
    return wait_job(id, seconds, [](const nlohmann::json& j) {
      const std::string state = j.at("state");
      return state == "done" || state == "failed" || state == "canceled";
    });
  }

  // Pixels and channel names equal, bit for bit.
  static void expect_bitwise_equal(const std::filesystem::path& a, const std::filesystem::path& b) {
    const LayeredImage x = read_exr(a), y = read_exr(b);
    ASSERT_EQ(x.channels, y.channels) << a << " vs " << b;
    ASSERT_EQ(x.pixels.size(), y.pixels.size());
    EXPECT_EQ(std::memcmp(x.pixels.data(), y.pixels.data(), x.pixels.size() * sizeof(float)), 0)
        << a << " and " << b << " differ";
  }

  std::unique_ptr<BackgroundProcess> server_;
  std::map<std::string, std::unique_ptr<BackgroundProcess>> workers_;
  std::string url_, submitter_, worker_token_;
  int port_ = 0, server_starts_ = 0;
};

}  // namespace vesper::test
