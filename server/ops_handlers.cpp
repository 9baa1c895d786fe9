#include "server/handlers.h"

#include "server/locked_store.h"
#include "server/metrics.h"
#include "server/worker_registry.h"

namespace vesper {
namespace {

ApiResponse metrics(const OpsHandlerDeps& d, const ApiRequest&) {
  MetricsSnapshot m;
  for (TaskState s : {TaskState::Queued, TaskState::Leased, TaskState::Done, TaskState::Failed,
                      TaskState::Canceled, TaskState::Paused})
    m.tasks_by_state[to_string(s)] = 0;
  d.store.read([&](const JobStore& s) {
    const auto jobs = s.jobs();
    m.jobs = int64_t(jobs.size());
    for (const auto& j : jobs) {
      m.tasks_by_state[to_string(TaskState::Queued)] += j.queued;
      m.tasks_by_state[to_string(TaskState::Leased)] += j.leased;
      m.tasks_by_state[to_string(TaskState::Done)] += j.done;
      m.tasks_by_state[to_string(TaskState::Failed)] += j.failed;
      m.tasks_by_state[to_string(TaskState::Canceled)] += j.canceled;
      m.tasks_by_state[to_string(TaskState::Paused)] += j.paused;
    }
  });
  m.workers = int64_t(d.workers.list().size());
  d.counters.fill(m);
  return text_response(prometheus_text(m), "text/plain; version=0.0.4; charset=utf-8");
}

}  // namespace

void add_ops_handlers(HandlerTable& table, const OpsHandlerDeps& d) {
  table[protocol::Endpoint::Healthz] = [](const ApiRequest&) {
    return text_response("ok\n", "text/plain");
  };
  table[protocol::Endpoint::Metrics] = [d](const ApiRequest& r) { return metrics(d, r); };
}

}  // namespace vesper
