// Reads configs/farm.toml-style files with toml++ (the only file including it).
#include "cli/farm_config.h"

#include <toml++/toml.h>
#include <cstdlib>
#include <functional>
#include <map>

#include "common/sha256.h"

namespace vesper::cli {
namespace {

// One setter per key: checks the node's type and range, or throws the reason.
using Setter = std::function<void(const toml::node&)>;

Setter str(std::string& out) {
  return [&out](const toml::node& n) {
    if (!n.is_string()) throw std::invalid_argument("expected a string");
    out = *n.value<std::string>();
    if (out.empty()) throw std::invalid_argument("expected a non-empty string");
  };
}

Setter integer(int& out, long long lo, long long hi) {
  return [&out, lo, hi](const toml::node& n) {
    if (!n.is_integer()) throw std::invalid_argument("expected an integer");
    const long long v = *n.value<int64_t>();
    if (v < lo || v > hi)
      throw std::invalid_argument("expected an integer in [" + std::to_string(lo) + ", " +
                                  std::to_string(hi) + "], got " + std::to_string(v));
    out = int(v);
  };
}

Setter bytes(int64_t& out, int64_t lo) {
  return [&out, lo](const toml::node& n) {
    if (!n.is_integer()) throw std::invalid_argument("expected an integer (bytes)");
    const int64_t v = *n.value<int64_t>();
    if (v < lo)
      throw std::invalid_argument("expected at least " + std::to_string(lo) + " bytes, got " +
                                  std::to_string(v));
    out = v;
  };
}

Setter number(double& out, double lo, double hi) {
  return [&out, lo, hi](const toml::node& n) {
    if (!n.is_number()) throw std::invalid_argument("expected a number");
    const double v = *n.value<double>();
    if (!(v >= lo && v <= hi))
      throw std::invalid_argument("expected a number in [" + std::to_string(lo) + ", " +
                                  std::to_string(hi) + "], got " + std::to_string(v));
    out = v;
  };
}

Setter boolean(bool& out) {
  return [&out](const toml::node& n) {
    if (!n.is_boolean()) throw std::invalid_argument("expected true or false");
    out = *n.value<bool>();
  };
}

// An http:// or https:// URL, or empty (= off).
Setter optional_url(std::string& out) {
  return [&out](const toml::node& n) {
    if (!n.is_string()) throw std::invalid_argument("expected a string");
    const std::string v = *n.value<std::string>();
    if (!v.empty() && v.rfind("http://", 0) != 0 && v.rfind("https://", 0) != 0)
      throw std::invalid_argument("expected an http:// or https:// URL (or \"\" for none), got '" +
                                  v + "'");
    out = v;
  };
}

// An array of SHA-256 hex digests (renderer builds).
Setter sha256_list(std::vector<std::string>& out) {
  return [&out](const toml::node& n) {
    const toml::array* a = n.as_array();
    if (!a) throw std::invalid_argument("expected an array of sha256 hex strings");
    out.clear();
    for (const toml::node& e : *a) {
      const auto v = e.value<std::string>();
      if (!e.is_string() || !is_sha256_hex(*v))
        throw std::invalid_argument(
            "expected 64 lower-case hex digits (sha256sum of a vesper binary), got " +
            (e.is_string() ? "'" + *v + "'" : std::string("a non-string")));
      out.push_back(*v);
    }
  };
}

std::map<std::string, std::map<std::string, Setter>> setters(FarmSettings& s) {
  return {
      {"server",
       {{"host", str(s.server.host)},
        {"port", integer(s.server.port, 0, 65535)},
        {"data_dir", str(s.server.data_dir)},
        {"lease_seconds", number(s.server.lease_seconds, 1, 86400)},
        {"blocklist_threshold", integer(s.server.blocklist_threshold, 1, 1000)},
        {"max_blob_mib", integer(s.server.max_blob_mib, 1, 16384)},
        {"threads", integer(s.server.threads, 1, 1024)},
        {"max_connections", integer(s.server.max_connections, 1, 100000)},
        {"header_timeout", number(s.server.header_timeout, 0.1, 3600)},
        {"idle_timeout", number(s.server.idle_timeout, 0.1, 3600)},
        {"task_timeout", number(s.server.task_timeout, 0, 30 * 86400)},
        {"trusted_renderers", sha256_list(s.server.trusted_renderers)},
        {"monitor_read_only", boolean(s.server.monitor_read_only)},
        {"blob_grace_seconds", number(s.server.blob_grace_seconds, 0, 365 * 86400.0)},
        {"webhook_url", optional_url(s.server.webhook_url)}}},
      {"worker",
       {{"server", str(s.worker.server)},
        {"cache_dir", str(s.worker.cache_dir)},
        {"heartbeat_seconds", number(s.worker.heartbeat_seconds, 0.05, 3600)},
        {"idle_backoff_min", number(s.worker.idle_backoff_min, 0.001, 3600)},
        {"idle_backoff_max", number(s.worker.idle_backoff_max, 0.001, 3600)},
        {"render_threads", integer(s.worker.render_threads, 0, 4096)},
        {"kill_grace_seconds", number(s.worker.kill_grace_seconds, 0, 3600)},
        {"cache_max_bytes", bytes(s.worker.cache_max_bytes, 1 << 20)}}},
      {"job",
       {{"frames", str(s.job.frames)},
        {"spp", integer(s.job.spp, 0, 1 << 20)},
        {"samples_per_task", integer(s.job.samples_per_task, 0, 1 << 20)},
        {"priority", integer(s.job.priority, -1000000, 1000000)},
        {"max_attempts", integer(s.job.max_attempts, 1, 100)},
        {"noise_target", number(s.job.noise_target, 0, 1e9)},
        {"min_spp", integer(s.job.min_spp, 0, 1 << 20)},
        {"max_spp", integer(s.job.max_spp, 0, 1 << 20)},
        {"time_limit", number(s.job.time_limit, 0, 1e9)},
        {"task_timeout", number(s.job.task_timeout, 0, 30 * 86400)}}},
      {"up",
       {{"workers", integer(s.up.workers, 1, 256)},
        {"data_dir", str(s.up.data_dir)},
        {"output_dir", str(s.up.output_dir)}}},
  };
}

}  // namespace

FarmSettings load_farm_settings(const std::filesystem::path& file) {
  FarmSettings s;
  if (file.empty()) return s;
  const std::string name = file.string();
  toml::table doc;
  try {
    doc = toml::parse_file(name);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw FarmConfigError(name + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) +
                          ": " + std::string(e.description()));
  }
  auto table_setters = setters(s);
  for (auto&& [section_key, section] : doc) {
    const std::string section_name(section_key.str());
    const auto it = table_setters.find(section_name);
    if (it == table_setters.end())
      throw FarmConfigError(name + ": [" + section_name +
                            "]: unknown section (expected server, worker, job or up)");
    if (!section.is_table())
      throw FarmConfigError(name + ": " + section_name + ": expected a [" + section_name +
                            "] table");
    for (auto&& [key, value] : *section.as_table()) {
      const std::string key_name(key.str());
      const auto setter = it->second.find(key_name);
      if (setter == it->second.end())
        throw FarmConfigError(name + ": " + section_name + "." + key_name +
                              ": unknown key (configs/farm.toml lists every key)");
      try {
        setter->second(value);
      } catch (const std::invalid_argument& e) {
        throw FarmConfigError(name + ": " + section_name + "." + key_name + ": " + e.what());
      }
    }
  }
  if (s.worker.idle_backoff_min > s.worker.idle_backoff_max)
    throw FarmConfigError(name + ": worker.idle_backoff_min: expected <= idle_backoff_max");
  return s;
}

std::filesystem::path expand_user(const std::string& path) {
  if (path == "~" || path.rfind("~/", 0) == 0) {
    const char* home = std::getenv("HOME");
    if (home && *home) return std::filesystem::path(home) / path.substr(path.size() > 1 ? 2 : 1);
  }
  return path;
}

}  // namespace vesper::cli
