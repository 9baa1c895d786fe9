#pragma once
// The job endpoints (submitter token): submit, list, one job with its tasks,
// cancel/pause/resume/retry-failed, a task's log.
#include "server/http_exchange.h"

namespace vesper {

class BlobStore;
class LeaseTracker;
class LockedStore;
class ServerClock;

class JobHandlers {
 public:
  JobHandlers(LockedStore& store, const BlobStore& blobs, const LeaseTracker& leases,
              ServerClock& clock)
      : store_(store), blobs_(blobs), leases_(leases), clock_(clock) {}

  void add_to(HandlerTable& table);

 private:
  ApiResponse submit(const ApiRequest& req);
  ApiResponse list(const ApiRequest& req);
  ApiResponse get(const ApiRequest& req);
  ApiResponse act(const ApiRequest& req, protocol::JobAction action);
  ApiResponse task_log(const ApiRequest& req);

  LockedStore& store_;
  const BlobStore& blobs_;
  const LeaseTracker& leases_;
  ServerClock& clock_;
};

}  // namespace vesper
