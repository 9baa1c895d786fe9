// vesper tokens: the operator's view of the farm's worker tokens
// (server/tokens.h). Edits replace tokens.json atomically with mode 0600; a
// running server re-reads the file at its next request, so a revoked token
// is refused without a restart.
#include <spdlog/spdlog.h>

#include <cstdio>

#include "cli/commands.h"
#include "cli/farm_config.h"
#include "cli/farm_setup.h"
#include "common/control_characters.h"
#include "common/secret_token.h"
#include "server/tokens.h"

namespace vesper::cli {
namespace {

int list(const Tokens& t) {
  std::printf("shared worker token: %s\n", t.shared_worker_enabled ? "enabled" : "disabled");
  for (const auto& [name, w] : t.workers)
    std::printf("worker %s: %s\n", escape_control_characters(name).c_str(),
                w.enabled ? "enabled" : "revoked");
  return 0;
}

}  // namespace

int run_tokens(const TokensCommandOptions& o) {
  FarmSettings settings;
  try {
    settings = load_farm_settings(o.farm.config);
  } catch (const FarmConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  const std::filesystem::path file =
      expand_user(o.data_dir ? *o.data_dir : settings.server.data_dir) / "tokens.json";
  try {
    if (!std::filesystem::exists(file)) {
      spdlog::error(
          "{}: no such file (start `vesper server` once with this data dir, or pass "
          "--data-dir)",
          file.string());
      return 1;
    }
    Tokens t = read_tokens(file);
    if (o.action == "list") return list(t);
    if (o.action == "add-worker") {
      if (o.name.empty() || !control_character_problem(o.name).empty()) {
        spdlog::error("add-worker: the name must be non-empty text without control characters");
        return 2;
      }
      const auto it = t.workers.find(o.name);
      if (it != t.workers.end() && it->second.enabled) {
        spdlog::error("worker '{}' has an enabled token already; revoke it first to replace it",
                      o.name);
        return 1;
      }
      t.workers[o.name] = {random_hex(32), true};
      write_tokens(file, t);
      // stdout: the token alone, for scripts (give it to that worker as --token).
      std::printf("%s\n", t.workers[o.name].token.c_str());
      return 0;
    }
    if (o.action == "revoke") {
      const auto it = t.workers.find(o.name);
      if (it == t.workers.end()) {
        spdlog::error("no worker token named '{}' in {} (`vesper tokens list`)",
                      escape_control_characters(o.name), file.string());
        return 1;
      }
      it->second.enabled = false;
    } else {
      t.shared_worker_enabled = o.action == "enable-shared";
    }
    write_tokens(file, t);
    spdlog::info("{}: {} (a running server applies it at its next request)", file.string(),
                 o.action == "revoke" ? "revoked '" + o.name + "'" : o.action);
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

}  // namespace vesper::cli
