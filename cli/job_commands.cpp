// vesper cancel | pause | resume | workers | retry | logs | fetch: a job on
// the farm (vesper status: job_status.cpp).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

#include "cli/commands.h"
#include "cli/fetch.h"
#include "cli/job_client.h"
#include "cli/job_watch.h"
#include "common/control_characters.h"
#include "jobs/frame_range.h"
#include "protocol/job_messages.h"
#include "protocol/ops_messages.h"
#include "protocol/paths.h"

namespace vesper::cli {
namespace {

const std::string kWorkersPath(protocol::paths::kWorkers);

// A log for a terminal: line by line, each line's control characters
// escaped (a render's stderr may carry anything).
std::string printable_log(const std::string& log) {
  std::string out;
  size_t begin = 0;
  for (size_t end; (end = log.find('\n', begin)) != std::string::npos; begin = end + 1)
    out += escape_control_characters(log.substr(begin, end - begin)) + "\n";
  return out + escape_control_characters(log.substr(begin));
}

protocol::JobActionResponse post_action(FarmClient& c, int64_t job, protocol::JobAction action) {
  return c.post_json(protocol::job_action_path(job, action), nlohmann::json::object())
      .get<protocol::JobActionResponse>();
}

int job_action(const JobCommandOptions& o, protocol::JobAction action, const char* done) {
  return with_client(o, [&](FarmClient& c) {
    spdlog::info("{}: {}", done, describe_job(post_action(c, *o.job, action).job));
    return 0;
  });
}

}  // namespace

int run_cancel(const JobCommandOptions& o) {
  return job_action(o, protocol::JobAction::Cancel, "canceled");
}
int run_pause(const JobCommandOptions& o) {
  return job_action(o, protocol::JobAction::Pause, "paused");
}
int run_resume(const JobCommandOptions& o) {
  return job_action(o, protocol::JobAction::Resume, "resumed");
}

namespace {
// "job 3 task 17", or "-" for an idle worker.
std::string current_task(const protocol::WorkerInfo& w) {
  if (!w.current_task) return "-";
  return fmt::format("job {} task {}", w.current_task->job, w.current_task->task);
}

std::string blocklisted_for(const protocol::WorkerInfo& w) {
  return w.blocklisted_for.empty() ? "-" : fmt::format("{}", fmt::join(w.blocklisted_for, ","));
}

int prune_workers(FarmClient& c) {
  const auto names = worker_names(c);  // before they go
  const auto r = c.post_json(std::string(protocol::paths::kWorkersPrune), nlohmann::json::object())
                     .get<protocol::PruneResponse>();
  std::printf("pruned %zu offline or lost worker(s)\n", r.pruned.size());
  for (const std::string& id : r.pruned) {
    const auto it = names.find(id);
    std::printf("  %s %s\n", it == names.end() ? "?" : it->second.c_str(),
                escape_control_characters(id).c_str());
  }
  return 0;
}
}  // namespace

int run_workers(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    if (o.prune) return prune_workers(c);
    const nlohmann::json answer = c.get_json(kWorkersPath);
    if (o.json) {
      std::printf("%s\n", answer.dump(2).c_str());
      return 0;
    }
    const auto all = answer.get<protocol::WorkerList>();
    if (all.workers.empty())
      std::printf("no workers\n");
    else
      std::printf("%-24s %-34s %-8s %12s  %-22s %s\n", "name", "worker id", "state", "last seen",
                  "current task", "blocked for jobs");
    for (const protocol::WorkerInfo& w : all.workers)
      std::printf("%-24s %-34s %-8s %10.0fs ago  %-22s %s\n",
                  escape_control_characters(w.name).c_str(),
                  escape_control_characters(w.worker_id).c_str(),
                  escape_control_characters(w.state.empty() ? "?" : w.state).c_str(),
                  all.now - w.last_seen, current_task(w).c_str(), blocklisted_for(w).c_str());
    return 0;
  });
}

int run_retry(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    const auto a = post_action(c, *o.job, protocol::JobAction::RetryFailed);
    spdlog::info("requeued {} failed tasks: {}", a.requeued.value_or(0), describe_job(a.job));
    return 0;
  });
}

namespace {
// Every task's log tail, each headed by its task, frame, state and attempts.
int print_all_logs(FarmClient& c, int64_t job) {
  const auto j = c.get_job(job);
  int shown = 0;
  for (const protocol::TaskInfo& t : j.tasks) {
    if (!t.has_log) continue;
    std::printf("=== task %lld (frame %d, samples [%d, %d)), %s, attempts: %d ===\n%s\n",
                static_cast<long long>(t.id), t.frame, t.sample_begin, t.sample_end,
                t.state.c_str(), t.attempts,
                printable_log(c.get_text(protocol::task_log_path(job, t.id))).c_str());
    ++shown;
  }
  if (shown == 0) spdlog::info("job {}: no task has a log yet", job);
  return 0;
}
}  // namespace

int run_logs(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    if (!o.task) return print_all_logs(c, *o.job);
    const std::string log = c.get_text(protocol::task_log_path(*o.job, *o.task));
    if (log.empty()) spdlog::info("job {}: task {} has no log yet", *o.job, *o.task);
    std::printf("%s", printable_log(log).c_str());
    if (!log.empty() && log.back() != '\n') std::printf("\n");
    return 0;
  });
}

int run_fetch(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    const FetchedFrames f = fetch_frames(c, *o.job, o.output_dir);
    for (const auto& p : f.written) std::printf("%s\n", p.string().c_str());
    if (!f.missing.empty()) {
      spdlog::warn("job {}: frames not ready (pending or failed): {}", *o.job,
                   format_frame_list(f.missing));
      return 3;
    }
    return 0;
  });
}

}  // namespace vesper::cli

namespace vesper::cli {

// Deletes a finished (or, with --cancel, any) job; the server frees the
// blobs no remaining job references.
int run_delete(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    if (o.cancel_first) post_action(c, *o.job, protocol::JobAction::Cancel);
    const auto r = c.delete_json(protocol::job_path(*o.job)).get<protocol::DeleteJobResponse>();
    spdlog::info("deleted job {}: {} blob(s) freed, {:.1f} MB", r.deleted, r.blobs_freed,
                 double(r.bytes_freed) / 1e6);
    return 0;
  });
}

}  // namespace vesper::cli
