#pragma once
// Settings -> the library configs, shared by `vesper server`, `vesper worker`
// and `vesper up` so each key of configs/farm.toml is applied in one place.
#include <filesystem>

#include "cli/farm_config.h"
#include "server/server.h"
#include "worker/worker.h"

namespace vesper::cli {

// Every [server] key (host, port, data_dir expanded, lease, blocklist, limits, threads).
ServerConfig server_config(const FarmSettings& settings);
// Every [worker] key but the server URL and token; renders with this executable.
WorkerConfig worker_config(const FarmSettings& settings);
// This executable (/proc/self/exe), for child renders and merges.
std::filesystem::path self_executable();
// Installs `handler` for SIGINT and SIGTERM (it must be async-signal-safe).
void on_stop_signals(void (*handler)(int));
// For those handlers: the first stop signal is a graceful stop (the handler's
// job); a second one ends the process at once — its renders die with it
// (parent_watch.h) and their leases expire on the server. Returns normally
// on the first signal only.
void exit_on_second_signal();

}  // namespace vesper::cli
