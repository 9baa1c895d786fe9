// vesper worker: pull tasks from a server and render them until SIGINT/SIGTERM.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>

#include "cli/commands.h"
#include "cli/farm_client.h"
#include "cli/farm_config.h"
#include "cli/farm_setup.h"
#include "cli/parent_watch.h"
#include "worker/worker.h"

namespace vesper::cli {
namespace {

Worker* g_worker = nullptr;

// Async-signal-safe: request_stop only sets an atomic flag. The render in
// progress is finished and reported; a second signal ends the worker at once
// (its render dies with it, its lease expires).
extern "C" void on_stop_signal(int) {
  exit_on_second_signal();
  if (g_worker) g_worker->request_stop();
}

}  // namespace

int run_worker(const WorkerCommandOptions& o) {
  WorkerConfig c;
  try {
    const FarmSettings settings = load_farm_settings(o.farm.config);
    c = worker_config(settings);
    c.server_url = resolve_server_url(settings, o.farm.server);
    c.token = resolve_token(settings, c.server_url, o.farm.token, TokenRole::Worker);
    if (o.cache_dir) c.cache_dir = expand_user(*o.cache_dir);
    if (o.threads) c.render_threads = *o.threads;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (o.name) c.name = *o.name;
  if (o.renderer) {
    c.vesper_binary = *o.renderer;
    c.reuse_results = false;  // a wrapper's hash does not pin what it runs
  }
  c.max_tasks = o.max_tasks;
  c.exit_when_idle = o.exit_when_idle;

  export_parent_pid();  // its renders die with it (parent_watch.h)
  Worker worker(c);
  g_worker = &worker;
  on_stop_signals(on_stop_signal);
  spdlog::info("worker: pulling from {} (cache {})", c.server_url, c.cache_dir.string());
  const int rc = worker.run();
  g_worker = nullptr;
  spdlog::info("worker: {} tasks completed, {} failed, {} dropped", worker.tasks_completed(),
               worker.tasks_failed(), worker.tasks_dropped());
  return rc;
}

}  // namespace vesper::cli
