#pragma once
// The handlers, one group per resource, each given only the parts of the
// server it needs. A group adds its endpoints to a HandlerTable; its .cpp
// holds the handlers.
#include <functional>
#include <string>
#include <vector>

#include "server/http_exchange.h"

namespace vesper {

class BlobStore;
class FrameMerger;
class FrameViews;
class TokenFile;
class LeaseTracker;
class LockedStore;
class ResultExpectations;
class ServerClock;
class ServerCounters;
class WorkerRegistry;

// Jobs (submitter token): submit, list, one job with its tasks and frames,
// cancel/pause/resume/retry-failed, a task's log. job_handlers.cpp
struct JobHandlerDeps {
  LockedStore& store;
  const BlobStore& blobs;
  const LeaseTracker& leases;  // progress of leased tasks
  const FrameMerger& merger;   // failed merges, for the frames' states
  ServerClock& clock;
  // The renderer builds trusted for result reuse: a new job's tasks
  // identical to tasks one of them rendered are done at submit.
  std::vector<std::string> reusable_renderers;
  // Tasks were completed (at submit, by reuse): frames may wait for a merge.
  std::function<void()> tasks_completed;
  ServerCounters& counters;  // tasks reused at submit
};
void add_job_handlers(HandlerTable& table, const JobHandlerDeps& deps);

// Workers (register, list) and the lease protocol (lease, heartbeat,
// complete, fail) with its fencing: a call on a stale lease is a 409 that
// never touches committed state. worker_handlers.cpp
struct WorkerHandlerDeps {
  LockedStore& store;
  const BlobStore& blobs;
  WorkerRegistry& workers;
  LeaseTracker& leases;
  ServerCounters& counters;
  ServerClock& clock;
  double lease_seconds;
  double default_task_timeout;  // for jobs without one; 0 = none
  // Tasks were completed: a frame of several tasks may be ready to merge (a
  // reused output may have noise to read).
  std::function<void()> tasks_completed;
  // Results are checked before they are committed (server/result_check.h);
  // nullptr: taken as uploaded (ServerConfig::verify_results off).
  ResultExpectations* expectations;
  // Whether results of this renderer build may be reused by other jobs.
  std::function<bool(const std::string&)> trusted_renderer;
};
void add_worker_handlers(HandlerTable& table, const WorkerHandlerDeps& deps);

// Frames (submitter token): every frame's state, a frame's EXR (merged by
// the FrameMerger when the frame was split), and for the monitor its PNG
// thumbnail and luminosity histogram (frame_views.h). frame_handlers.cpp
struct FrameHandlerDeps {
  LockedStore& store;
  const BlobStore& blobs;
  FrameMerger& merger;
  FrameViews& views;
};
void add_frame_handlers(HandlerTable& table, const FrameHandlerDeps& deps);

// Blobs (either token): PUT stores a body under its verified SHA-256, GET
// streams it (HEAD answers from the same handler). blob_handlers.cpp
void add_blob_handlers(HandlerTable& table, BlobStore& blobs);

// Operations: /healthz (no token), /metrics (Prometheus text). ops_handlers.cpp
struct OpsHandlerDeps {
  LockedStore& store;
  const WorkerRegistry& workers;
  const ServerCounters& counters;
};
void add_ops_handlers(HandlerTable& table, const OpsHandlerDeps& deps);

// The browser monitor: GET / and /monitor/{asset} from the files embedded at
// build time (server/monitor/), POST /login (the submitter token in, the
// session cookie out; server/monitor_auth.h) and POST /logout.
// monitor_handlers.cpp
void add_monitor_handlers(HandlerTable& table, TokenFile& tokens);
// Housekeeping (submitter token, goodbye: worker token): DELETE a job and
// collect the blobs no job references; a worker's goodbye; prune offline and
// lost workers. housekeeping_handlers.cpp
struct HousekeepingHandlerDeps {
  LockedStore& store;
  BlobStore& blobs;
  FrameViews& views;  // the monitor's views of collected blobs go with them
  WorkerRegistry& workers;
  ServerClock& clock;
  double lease_seconds;
  double blob_grace_seconds;  // an unclaimed upload is kept this long
};
void add_housekeeping_handlers(HandlerTable& table, const HousekeepingHandlerDeps& deps);

}  // namespace vesper
