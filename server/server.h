#pragma once
// The farm server: an HTTP JSON API under /api/v1 over the job store
// (jobs/), a content-addressed blob store, bearer tokens for submitters and
// workers, /metrics and /healthz. See server/README.md for the API.
//
// Data dir layout: tokens.json (0600), jobs.sqlite (+WAL), workers.json,
// blobs/ab/cdef... (+ blobs/tmp/), merge-tmp/ (merges in flight),
// monitor-cache/ (the monitor's thumbnails and histograms, by output blob).
//
// The HTTP layer is http_api.* over http_connections.* (server/README.md,
// "Connections").
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace vesper {

struct ServerConfig {
  std::filesystem::path data_dir;
  std::string host = "127.0.0.1";  // loopback unless configured otherwise
  int port = 0;                    // 0 = an ephemeral port (start() returns it)
  double lease_seconds = 60;
  // Seconds one render of a task may take when its job sets no
  // task_timeout (the farm default): the worker kills a longer render and
  // fails that attempt. 0 = no default limit.
  double task_timeout = 86400;
  int blocklist_threshold = 3;
  std::size_t max_blob_bytes = std::size_t(64) << 20;  // PUT /blobs bodies; 413 beyond
  std::size_t max_json_bytes = std::size_t(1) << 20;   // JSON bodies; 413 beyond
  // Requests handled at once (body read + handler); more wait for a slot.
  // Connections are not bounded by it (see max_connections): an open
  // connection only holds a sleeping thread of the connection layer.
  int threads = 16;
  // Open connections; one beyond is answered 503 and closed at once.
  int max_connections = 1024;
  // Seconds for a whole request head (from accept, or from its first byte on
  // a kept-alive connection): 408 and closed beyond. Bigger heads: 431.
  double header_timeout = 10;
  std::size_t max_header_bytes = std::size_t(64) << 10;
  // Seconds a kept-alive connection may wait idle for its next request.
  double idle_timeout = 5;
  // Seconds a body read or response write may go without progress.
  double io_timeout = 30;
  // Seconds for the job store's `now` (lease expiry). Empty: the wall clock
  // (seconds since the Unix epoch) clamped so it never goes backwards within
  // the process. A wall clock rather than a boot-relative one, because lease
  // expiries are persisted and must stay meaningful across a server restart.
  std::function<double()> clock;
  // How often expired leases are requeued in the background (seconds);
  // 0 = lease_seconds / 4, at most 5 s. Leasing also requeues them.
  double reaper_interval = 0;
  // The `vesper` executable that merges a frame's sample-range results
  // (`vesper merge`). Empty: `vesper` next to this process's executable
  // (/proc/self/exe). If there is none, merged frames of several tasks are
  // unavailable (503); frames of one task still work.
  std::filesystem::path vesper_binary;
  // A failed merge is retried on request only after this many seconds.
  double merge_retry_seconds = 60;
  // Check each result before committing it: a readable EXR (whole frame) or
  // partial (sample range) whose metadata names the task's scene hash,
  // frame, sample range and seed; otherwise 400 and the attempt fails
  // (server/result_check.h). Off only for tests and benchmarks that upload
  // fake bytes on purpose.
  bool verify_results = true;
  // Renderer builds (sha256 of the worker's renderer executable) whose
  // results later identical jobs may reuse. A worker announcing another
  // build renders as usual, but its results are never reused.
  std::vector<std::string> trusted_renderers;
  // Trust this server's own executable's build too (the `vesper` binary that
  // workers of the same installation run).
  bool trust_own_build = true;
  // The browser monitor (GET /): with this set, its reads (jobs, tasks and
  // their logs, frames' states, thumbnails and histograms, workers) need no
  // token, for a wall screen; its actions still need a login. Frames' EXRs
  // and blobs always need a token (server/monitor_auth.h).
  bool monitor_read_only = false;
  // Seconds a blob uploaded but not yet referenced by any job (a client
  // uploads before it submits) survives garbage collection.
  double blob_grace_seconds = 3600;
  // Every job that ends (done, failed, canceled) is announced with a POST of
  // JSON to this URL (server/job_webhook.h). Empty: no webhook.
  std::string webhook_url;
};

class Server {
 public:
  // Creates the data dir if needed, creates or reads the token file, opens
  // (and migrates) the job store. Throws on a bad data dir or token file.
  explicit Server(ServerConfig config);
  ~Server();  // stops
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Binds and serves on a background thread; returns the bound port. Throws
  // if the address cannot be bound. Call at most once per Server.
  int start();
  // Stops serving and waits for the server thread; idempotent.
  void stop();

  int port() const;
  std::string url() const;  // http://host:port
  std::string submitter_token() const;
  std::string worker_token() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace vesper
