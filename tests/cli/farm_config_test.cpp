// configs/farm.toml documents every farm setting: it must parse, set every key,
// and equal the built-in defaults; bad files name the file, key and problem.
#include "cli/farm_config.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/common/temp_dir.h"

namespace vesper::cli {
namespace {

bool operator==(const FarmServerSettings& a, const FarmServerSettings& b) {
  return a.host == b.host && a.port == b.port && a.data_dir == b.data_dir &&
         a.lease_seconds == b.lease_seconds && a.blocklist_threshold == b.blocklist_threshold &&
         a.max_blob_mib == b.max_blob_mib && a.threads == b.threads &&
         a.task_timeout == b.task_timeout && a.trusted_renderers == b.trusted_renderers &&
         a.max_connections == b.max_connections && a.header_timeout == b.header_timeout &&
         a.idle_timeout == b.idle_timeout && a.monitor_read_only == b.monitor_read_only &&
         a.blob_grace_seconds == b.blob_grace_seconds && a.webhook_url == b.webhook_url;
}
bool operator==(const FarmWorkerSettings& a, const FarmWorkerSettings& b) {
  return a.server == b.server && a.cache_dir == b.cache_dir &&
         a.heartbeat_seconds == b.heartbeat_seconds && a.idle_backoff_min == b.idle_backoff_min &&
         a.idle_backoff_max == b.idle_backoff_max && a.render_threads == b.render_threads &&
         a.kill_grace_seconds == b.kill_grace_seconds && a.cache_max_bytes == b.cache_max_bytes;
}
bool operator==(const FarmJobSettings& a, const FarmJobSettings& b) {
  return a.frames == b.frames && a.spp == b.spp && a.samples_per_task == b.samples_per_task &&
         a.priority == b.priority && a.max_attempts == b.max_attempts &&
         a.noise_target == b.noise_target && a.min_spp == b.min_spp && a.max_spp == b.max_spp &&
         a.time_limit == b.time_limit && a.task_timeout == b.task_timeout;
}
bool operator==(const FarmUpSettings& a, const FarmUpSettings& b) {
  return a.workers == b.workers && a.data_dir == b.data_dir && a.output_dir == b.output_dir;
}

const std::filesystem::path kShipped = std::string(VESPER_SOURCE_DIR) + "/configs/farm.toml";

TEST(FarmConfig, ShippedFileEqualsTheBuiltInDefaults) {
  const FarmSettings file = load_farm_settings(kShipped), defaults;
  EXPECT_TRUE(file.server == defaults.server);
  EXPECT_TRUE(file.worker == defaults.worker);
  EXPECT_TRUE(file.job == defaults.job);
  EXPECT_TRUE(file.up == defaults.up);
}

TEST(FarmConfig, ShippedFileSetsEveryKey) {
  // Count `key = value` lines: one per setter (15 server, 8 worker, 10 job, 3 up).
  std::ifstream in(kShipped);
  int keys = 0;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#' && line[0] != '[' && line.find(" = ") != std::string::npos)
      ++keys;
  EXPECT_EQ(keys, 36);
}

class FarmConfigErrors : public ::testing::Test {
 protected:
  std::string error_of(const std::string& text) {
    const test::TempDir dir("farm-config");
    const auto p = dir / "farm.toml";
    std::ofstream(p) << text;
    try {
      load_farm_settings(p);
    } catch (const FarmConfigError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(FarmConfigErrors, NameTheFileKeyAndProblem) {
  EXPECT_NE(error_of("[server]\nlease = 3\n").find(".toml: server.lease: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("[server]\nport = \"80\"\n").find("server.port: expected an integer"),
            std::string::npos);
  EXPECT_NE(error_of("[server]\nport = 70000\n")
                .find("server.port: expected an integer in [0, "
                      "65535], got 70000"),
            std::string::npos);
  EXPECT_NE(error_of("[servers]\n").find("[servers]: unknown section"), std::string::npos);
  EXPECT_NE(error_of("[job]\nmax_attempts = 0\n").find("job.max_attempts"), std::string::npos);
  EXPECT_NE(error_of("[server\n").find(".toml:1:"), std::string::npos);  // syntax: line:column
  EXPECT_NE(error_of("[worker]\nidle_backoff_min = 9.0\n").find("idle_backoff_min"),
            std::string::npos);
  EXPECT_EQ(error_of("[server]\nport = 9000\n[worker]\nheartbeat_seconds = 1\n"), "");
  EXPECT_NE(error_of("[server]\nwebhook_url = \"ftp://x\"\n")
                .find("server.webhook_url: expected an http:// or https:// URL"),
            std::string::npos);
  EXPECT_EQ(error_of("[server]\nwebhook_url = \"http://127.0.0.1:9/hook\"\n"), "");
}

TEST(FarmConfig, FileValuesOverrideDefaults) {
  const test::TempDir dir("farm-config");
  const auto p = dir / "farm-override.toml";
  std::ofstream(p) << "[server]\nport = 9000\nlease_seconds = 7.5\n[up]\nworkers = 4\n";
  const FarmSettings s = load_farm_settings(p);
  EXPECT_EQ(s.server.port, 9000);
  EXPECT_EQ(s.server.lease_seconds, 7.5);
  EXPECT_EQ(s.up.workers, 4);
  EXPECT_EQ(s.server.host, "127.0.0.1");  // untouched keys keep their defaults
}

TEST(FarmConfig, ExpandUser) {
  ::setenv("HOME", "/home/artist", 1);
  EXPECT_EQ(expand_user("~/farm"), std::filesystem::path("/home/artist/farm"));
  EXPECT_EQ(expand_user("~"), std::filesystem::path("/home/artist/"));
  EXPECT_EQ(expand_user("out/farm"), std::filesystem::path("out/farm"));
}

}  // namespace
}  // namespace vesper::cli
