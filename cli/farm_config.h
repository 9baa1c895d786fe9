#pragma once
// The farm's settings: built-in defaults (documented key by key in
// configs/farm.toml) overridden by an optional TOML file, then by flags.
// toml++ is included by farm_config.cpp only.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace vesper::cli {

struct FarmServerSettings {
  std::string host = "127.0.0.1";
  int port = 8765;
  std::string data_dir = "~/.local/share/vesper/farm";
  double lease_seconds = 60;
  int blocklist_threshold = 3;
  int max_blob_mib = 64;
  int threads = 16;  // requests handled at once
  int max_connections = 1024;
  double header_timeout = 10;   // seconds for a whole request head
  double idle_timeout = 5;      // seconds a kept-alive connection waits for its next request
  double task_timeout = 86400;  // the farm default for jobs without one; 0 = none
  // Renderer builds (sha256) whose results later identical jobs may reuse,
  // besides the server's own build.
  std::vector<std::string> trusted_renderers;
  // The browser monitor's reads without a token (a wall screen on a trusted network).
  bool monitor_read_only = false;
  double blob_grace_seconds = 3600;  // an upload no job references yet survives GC this long
  // Jobs that end are announced with a POST of JSON here; empty = off.
  std::string webhook_url;
};

struct FarmWorkerSettings {
  std::string server = "http://127.0.0.1:8765";
  std::string cache_dir = "~/.cache/vesper/worker";
  double heartbeat_seconds = 5;
  double idle_backoff_min = 0.2, idle_backoff_max = 5.0;
  int render_threads = 0;
  double kill_grace_seconds = 2.0;
  int64_t cache_max_bytes = int64_t(10) << 30;  // blob cache cap, LRU eviction
};

struct FarmJobSettings {
  std::string frames = "1";
  int spp = 0;  // 0 = the scene's render.spp
  int samples_per_task = 0;
  int priority = 50;
  int max_attempts = 3;
  // Per frame (docs/farm.md, "Noise targets and time limits"); 0 = the scene's.
  double noise_target = 0;
  int min_spp = 0, max_spp = 0;
  double time_limit = 0;
  double task_timeout = 0;  // seconds per task render; 0 = the server's default
};

struct FarmUpSettings {
  int workers = 2;
  std::string data_dir = "out/farm";
  std::string output_dir = "out/farm-frames";
};

struct FarmSettings {
  FarmServerSettings server;
  FarmWorkerSettings worker;
  FarmJobSettings job;
  FarmUpSettings up;
};

class FarmConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Defaults overridden by `file` (if not empty). Throws FarmConfigError
// "<file>: <key>: <what was expected>" for syntax errors, unknown keys, wrong
// types and out-of-range values.
FarmSettings load_farm_settings(const std::filesystem::path& file);

// `~` or `~/...` -> $HOME/...; other paths unchanged.
std::filesystem::path expand_user(const std::string& path);

}  // namespace vesper::cli
