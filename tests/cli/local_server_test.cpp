// `vesper status` (and every client) finds the token of a server on this
// machine started with --data-dir, with no --token and no $VESPER_TOKEN: the
// server records its URL and data dir while it runs (cli/local_server.h).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "farm_test_fixture.h"

namespace fs = std::filesystem;

namespace vesper::test {
namespace {

class LocalServer : public FarmTest {
 protected:
  // Records and the default data dir inside the test's folder, no token in
  // the environment; restored afterwards (other tests may share the process).
  void SetUp() override {
    FarmTest::SetUp();
    for (const char* var : {"XDG_STATE_HOME", "HOME", "VESPER_TOKEN", "VESPER_SERVER"}) {
      const char* v = std::getenv(var);
      saved_.emplace_back(var, v ? std::optional<std::string>(v) : std::nullopt);
      ::unsetenv(var);
    }
    ::setenv("XDG_STATE_HOME", (dir_ / "state").c_str(), 1);
    ::setenv("HOME", dir_.c_str(), 1);
  }
  void TearDown() override {
    FarmTest::TearDown();
    for (const auto& [var, value] : saved_)
      value ? ::setenv(var.c_str(), value->c_str(), 1) : ::unsetenv(var.c_str());
  }
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

TEST_F(LocalServer, StatusFindsTheTokenOfAServerStartedWithDataDir) {
  start_server(write_config(10));
  const fs::path record = dir_ / "state/vesper/servers" / (std::to_string(port_) + ".json");
  EXPECT_TRUE(fs::exists(record));

  const RunResult status = run("status --server " + url_);
  EXPECT_EQ(status.exit_code, 0) << status.err;
  const RunResult localhost =
      run("workers --server http://localhost:" + std::to_string(port_) + " -q");
  EXPECT_EQ(localhost.exit_code, 0) << localhost.err;

  // Stopped: the record goes, and the error says where the token was looked for.
  server_->signal(SIGTERM);
  ASSERT_EQ(server_->wait_for(20), 0);
  EXPECT_FALSE(fs::exists(record));
  const RunResult stopped = run("status --server " + url_);
  EXPECT_EQ(stopped.exit_code, 1);
  EXPECT_NE(stopped.err.find("tokens.json"), std::string::npos) << stopped.err;
}

TEST_F(LocalServer, ARecordOfADeadServerIsIgnored) {
  start_server(write_config(10));
  const fs::path record = dir_ / "state/vesper/servers" / (std::to_string(port_) + ".json");
  server_->signal(SIGKILL);
  server_->wait_for(20);
  ASSERT_TRUE(fs::exists(record));  // killed: no chance to remove it
  const RunResult r = run("status --server " + url_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.find((dir_ / "data").string()), std::string::npos)
      << "used the dead server's data dir: " << r.err;
}

}  // namespace
}  // namespace vesper::test
