#pragma once
// ServerTest: a farm server over real HTTP on 127.0.0.1 (an ephemeral port,
// a data dir of its own, a clock the test moves), with httplib::Client as
// the client and helpers for blobs, jobs and the worker protocol. Shared by
// the server suite's files.
#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "common/sha256.h"
#include "server/server.h"
#include "tests/common/http_blob.h"
#include "tests/common/temp_dir.h"

namespace vesper {

class ServerTest : public ::testing::Test {
 protected:
  using json = nlohmann::json;

  void SetUp() override { clock_ = std::make_shared<std::atomic<double>>(1000.0); }
  void TearDown() override { server_.reset(); }

  ServerConfig config() const {
    ServerConfig c;
    c.data_dir = dir_ / "data";
    c.lease_seconds = 10;
    // These tests complete tasks with made-up bytes ("the frame") on purpose;
    // result checks have their own tests (result_check_test.cpp).
    c.verify_results = false;
    auto clock = clock_;
    c.clock = [clock] { return clock->load(); };
    return c;
  }
  // (Re)starts the server on the same data dir.
  void start(ServerConfig c) {
    server_.reset();
    server_ = std::make_unique<Server>(std::move(c));
    port_ = server_->start();
    ASSERT_GT(port_, 0);
  }
  void start() { start(config()); }
  void advance(double seconds) { clock_->store(clock_->load() + seconds); }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(10);
    return c;
  }
  static httplib::Headers auth(const std::string& token) {
    return {{"Authorization", "Bearer " + token}};
  }
  httplib::Headers sub() const { return auth(server_->submitter_token()); }
  httplib::Headers wrk() const { return auth(server_->worker_token()); }

  httplib::Result post(const std::string& path, const json& body, const httplib::Headers& h) {
    return client().Post(("/api/v1" + path).c_str(), h, body.dump(), "application/json");
  }
  json post_ok(const std::string& path, const json& body, const httplib::Headers& h,
               int status = 200) {
    auto r = post(path, body, h);
    EXPECT_TRUE(r) << path;
    if (!r) return {};
    EXPECT_EQ(r->status, status) << path << ": " << r->body;
    return r->body.empty() ? json() : json::parse(r->body);
  }
  json get_ok(const std::string& path) {
    auto r = client().Get(("/api/v1" + path).c_str(), sub());
    EXPECT_TRUE(r);
    if (!r) return {};
    EXPECT_EQ(r->status, 200) << path << ": " << r->body;
    return json::parse(r->body);
  }
  // Uploads bytes as a blob; returns the hash.
  std::string put_blob(const std::string& bytes) {
    return test::upload_blob(client(), wrk(), bytes);
  }
  int64_t submit(int frames, int spp = 8, int split = 0, int max_attempts = 3) {
    const std::string scene = put_blob("{\"format\": \"vesper-scene/1\"}");
    json body{{"name", "test"},
              {"scene", scene},
              {"frames", "1-" + std::to_string(frames)},
              {"spp", spp},
              {"max_attempts", max_attempts}};
    if (split) body["samples_per_task"] = split;
    return post_ok("/jobs", body, sub(), 201).at("id").get<int64_t>();
  }
  std::string register_worker(const std::string& name) {
    return post_ok("/workers/register", {{"name", name}}, wrk()).at("worker_id");
  }
  json lease(const std::string& worker) {
    return post_ok("/lease", {{"worker_id", worker}}, wrk());
  }

  test::TempDir temp_{"server"};
  std::filesystem::path dir_ = temp_.path();
  std::shared_ptr<std::atomic<double>> clock_;
  std::unique_ptr<Server> server_;
  int port_ = 0;
};

}  // namespace vesper
