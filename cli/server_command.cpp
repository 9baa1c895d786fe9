// vesper server: the farm API in the foreground until SIGINT/SIGTERM.
#include <spdlog/spdlog.h>

#include <csignal>
#include <cstdio>

#include "cli/commands.h"
#include "cli/farm_config.h"
#include "cli/farm_setup.h"
#include "cli/local_server.h"
#include "common/sha256.h"
#include "server/server.h"

namespace vesper::cli {

int run_server(const ServerCommandOptions& o) {
  FarmSettings settings;
  try {
    settings = load_farm_settings(o.farm.config);
  } catch (const FarmConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  ServerConfig c = server_config(settings);
  if (o.data_dir) c.data_dir = expand_user(*o.data_dir);
  if (o.host) c.host = *o.host;
  if (o.port) c.port = *o.port;
  for (const std::string& sha : o.trusted_renderers) {
    if (!is_sha256_hex(sha)) {
      spdlog::error(
          "--trust-renderer '{}': expected 64 lower-case hex digits (sha256sum of a "
          "vesper binary)",
          sha);
      return 2;
    }
    c.trusted_renderers.push_back(sha);
  }

  // Block the stop signals before any thread starts (threads inherit the
  // mask), then wait for one here: no work in a signal handler.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  std::unique_ptr<Server> server;
  try {
    server = std::make_unique<Server>(c);
    server->start();
  } catch (const std::exception& e) {
    spdlog::error("server: {}", e.what());
    return 1;
  }
  spdlog::info("tokens for submitters and workers: {}; SIGINT/SIGTERM stops the server",
               (c.data_dir / "tokens.json").string());
  // Clients on this machine find the token of this data dir (local_server.h).
  record_local_server(server->url(), c.data_dir);
  std::printf("%s\n", server->url().c_str());
  std::fflush(stdout);
  int sig = 0;
  sigwait(&stop_signals, &sig);
  spdlog::info("server: {} received, stopping", sig == SIGTERM ? "SIGTERM" : "SIGINT");
  forget_local_server(server->url());
  server->stop();
  return 0;
}

}  // namespace vesper::cli
