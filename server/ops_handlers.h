#pragma once
// The operations endpoints: /healthz (no token) and /metrics (Prometheus
// text, either token), at the root and under /api/v1.
#include "server/http_exchange.h"

namespace vesper {

class LockedStore;
class ServerCounters;
class WorkerRegistry;

class OpsHandlers {
 public:
  OpsHandlers(LockedStore& store, const WorkerRegistry& workers, const ServerCounters& counters)
      : store_(store), workers_(workers), counters_(counters) {}
  void add_to(HandlerTable& table);

 private:
  ApiResponse metrics(const ApiRequest& req);

  LockedStore& store_;
  const WorkerRegistry& workers_;
  const ServerCounters& counters_;
};

}  // namespace vesper
