#pragma once
// The worker endpoints: register, list workers, and the lease protocol
// (lease, heartbeat, complete, fail) with its fencing: a call on a stale
// lease is a 409 that never touches committed state.
#include <functional>

#include "server/http_exchange.h"

namespace vesper {

class BlobStore;
class LeaseTracker;
class LockedStore;
class ServerClock;
class ServerCounters;
class WorkerRegistry;

class WorkerHandlers {
 public:
  struct Deps {
    LockedStore& store;
    const BlobStore& blobs;
    WorkerRegistry& workers;
    LeaseTracker& leases;
    ServerCounters& counters;
    ServerClock& clock;
    double lease_seconds;
    // Tasks were completed: a frame of several tasks may be ready to merge.
    std::function<void()> tasks_completed;
  };
  explicit WorkerHandlers(Deps deps) : d_(std::move(deps)) {}

  void add_to(HandlerTable& table);

 private:
  ApiResponse register_worker(const ApiRequest& req);
  ApiResponse list(const ApiRequest& req);
  ApiResponse lease(const ApiRequest& req);
  ApiResponse heartbeat(const ApiRequest& req);
  ApiResponse complete(const ApiRequest& req);
  ApiResponse fail(const ApiRequest& req);

  Deps d_;
};

}  // namespace vesper
