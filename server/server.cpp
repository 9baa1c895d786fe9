// The server: composes the stores, the lease tracker, the frame merger, the
// handlers (one group per resource) and the HTTP layer, and starts and stops
// them in order.
#include "server/server.h"

#include <spdlog/spdlog.h>

#include <mutex>
#include <set>

#include "common/sha256.h"

#include "jobs/job_store.h"
#include "server/blob_store.h"
#include "server/data_dir.h"
#include "server/frame_merger.h"
#include "server/frame_views.h"
#include "server/handlers.h"
#include "server/http_api.h"
#include "server/job_webhook.h"
#include "server/lease_tracker.h"
#include "server/locked_store.h"
#include "server/metrics.h"
#include "server/result_check.h"
#include "server/server_clock.h"
#include "server/tokens.h"
#include "server/worker_registry.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {

ServerConfig prepare(ServerConfig c) {
  if (c.data_dir.empty()) throw std::invalid_argument("server: data_dir is empty");
  make_data_dir_private(c.data_dir);
  if (c.lease_seconds <= 0) throw std::invalid_argument("server: lease_seconds must be positive");
  if (c.threads < 1) c.threads = 1;
  if (c.max_connections < 1)
    throw std::invalid_argument("server: max_connections must be positive");
  if (c.header_timeout <= 0 || c.idle_timeout <= 0 || c.io_timeout <= 0)
    throw std::invalid_argument(
        "server: header_timeout, idle_timeout and io_timeout must be positive");
  if (c.blob_grace_seconds < 0)
    throw std::invalid_argument("server: blob_grace_seconds must not be negative");
  if (c.max_header_bytes < 1024)
    throw std::invalid_argument("server: max_header_bytes must be at least 1024");
  return c;
}

std::unique_ptr<JobStore> open_store(const ServerConfig& c) {
  return std::make_unique<JobStore>(c.data_dir / "jobs.sqlite",
                                    StoreOptions{c.lease_seconds, c.blocklist_threshold});
}

// The renderer builds whose results may be reused: the configured ones and,
// unless told otherwise, this executable's own.
std::set<std::string> trusted_renderers(const ServerConfig& c) {
  std::set<std::string> out(c.trusted_renderers.begin(), c.trusted_renderers.end());
  if (c.trust_own_build) {
    if (const auto own = sha256_file("/proc/self/exe"))
      out.insert(*own);
    else
      spdlog::warn("server: cannot hash /proc/self/exe: its own build is not trusted for reuse");
  }
  return out;
}

}  // namespace

struct Server::Impl {
  ServerConfig config;
  TokenFile tokens;
  BlobStore blobs;
  std::set<std::string> trusted;
  ResultExpectations expectations;
  WorkerRegistry workers;
  LockedStore store;
  ServerClock clock;
  ServerCounters counters;
  LeaseTracker leases;
  FrameMerger merger;
  FrameViews views;
  std::unique_ptr<JobWebhook> webhook;  // null: no [server] webhook_url
  HttpApi http;  // last: stopped (and destroyed) before what its handlers use
  int bound_port = 0;
  bool started = false, stopped = false;
  std::mutex stop_mutex;

  explicit Impl(ServerConfig c)
      : config(prepare(std::move(c))),
        tokens(config.data_dir / "tokens.json"),
        blobs(config.data_dir / "blobs", config.blob_grace_seconds),
        trusted(trusted_renderers(config)),
        expectations(blobs),
        workers(config.data_dir / "workers.json"),
        store(open_store(config), open_store(config)),
        clock(config.clock),
        leases(store, clock, workers, config.lease_seconds),
        merger(FrameMergerConfig{config.data_dir, config.vesper_binary, config.merge_retry_seconds},
               store, blobs, clock),
        views(config.data_dir / "monitor-cache"),
        webhook(config.webhook_url.empty()
                    ? nullptr
                    : std::make_unique<JobWebhook>(WebhookOptions{config.webhook_url}, store)),
        http(config, tokens, counters) {}

  // Tasks were completed: frames may wait for a merge, a job may have ended.
  void tasks_completed() {
    merger.wake();
    if (webhook) webhook->wake();
  }

  HandlerTable handlers() {
    HandlerTable table;
    add_job_handlers(table, {store, blobs, leases, merger, clock,
                             std::vector<std::string>(trusted.begin(), trusted.end()),
                             [this] { tasks_completed(); }, counters});
    add_worker_handlers(
        table,
        {store, blobs, workers, leases, counters, clock, config.lease_seconds, config.task_timeout,
         [this] { tasks_completed(); }, config.verify_results ? &expectations : nullptr,
         [this](const std::string& r) { return !r.empty() && trusted.count(r) > 0; }});
    add_frame_handlers(table, {store, blobs, merger, views});
    add_blob_handlers(table, blobs);
    add_ops_handlers(table, {store, workers, counters});
    add_monitor_handlers(table, tokens);
    add_housekeeping_handlers(table, {store, blobs, views, workers, clock, config.lease_seconds,
                                      config.blob_grace_seconds});
    return table;
  }
};

Server::Server(ServerConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}

Server::~Server() { stop(); }

int Server::start() {
  Impl& s = *impl_;
  if (s.started) throw std::logic_error("Server::start called twice");
  s.started = true;
  s.http.route(s.handlers());
  // Before anything can expire a lease: while this server was down no worker
  // could heartbeat, and a lease lost to a restart would charge its task.
  if (const int renewed =
          s.store.with([&](JobStore& st) { return st.renew_leases(s.clock.now()); }))
    spdlog::info("renewed {} leases held before the restart", renewed);
  // Blobs jobs reference are not pending uploads (server/blob_store.h).
  s.blobs.claim(s.store.with([](JobStore& st) { return st.referenced_blobs(); }), BlobStore::now());
  s.bound_port = s.http.bind();
  s.http.serve();
  s.leases.start_reaper(s.config.reaper_interval > 0 ? s.config.reaper_interval
                                                     : std::min(5.0, s.config.lease_seconds / 4));
  s.merger.start();
  if (s.webhook)
    s.webhook->start();
  else  // without a webhook, jobs that end are not announced later, when one is set
    s.store.with([](JobStore& st) { st.mark_all_announced(); });
  spdlog::info("vesper server on http://{}:{} (data {})", s.config.host, s.bound_port,
               s.config.data_dir.string());
  return s.bound_port;
}

void Server::stop() {
  Impl& s = *impl_;
  {
    std::lock_guard lock(s.stop_mutex);
    const bool running = s.started && !s.stopped;
    s.stopped = true;
    if (!running) return;
  }
  // Merges in flight are killed and requests waiting for them answer 503,
  // so the HTTP threads can finish.
  s.merger.request_stop();
  s.http.stop();
  s.leases.stop_reaper();
  s.merger.join();
  if (s.webhook) s.webhook->stop();
  try {
    s.workers.save();
  } catch (const std::exception& e) {
    spdlog::error("saving workers: {}", e.what());
  }
}

int Server::port() const { return impl_->bound_port; }
std::string Server::url() const {
  return "http://" + impl_->config.host + ":" + std::to_string(impl_->bound_port);
}
std::string Server::submitter_token() const { return impl_->tokens.current()->submitter; }
std::string Server::worker_token() const { return impl_->tokens.current()->worker; }

}  // namespace vesper
