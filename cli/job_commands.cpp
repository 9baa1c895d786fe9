// vesper status | cancel | retry | logs | fetch: a job on the farm.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

#include "cli/commands.h"
#include "cli/fetch.h"
#include "cli/job_watch.h"
#include "common/control_characters.h"
#include "jobs/frame_range.h"
#include "protocol/job_messages.h"
#include "protocol/ops_messages.h"
#include "protocol/paths.h"

namespace vesper::cli {
namespace {

// Runs `body` with a client, turning the farm's errors into messages and exit codes.
template <typename Body>
int with_client(const JobCommandOptions& o, Body&& body) {
  try {
    const FarmSettings settings = load_farm_settings(o.farm.config);
    const std::string url = resolve_server_url(settings, o.farm.server);
    FarmClient client(url, resolve_token(settings, url, o.farm.token, TokenRole::Submitter));
    return body(client);
  } catch (const FarmConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

const std::string kWorkersPath(protocol::paths::kWorkers);

// The noise each finished frame reached, from its output's metadata (only
// when some frame's output says: a noise target or a time limit).
void print_frame_noise(const std::vector<protocol::FrameInfo>& frames) {
  auto says = [](const protocol::FrameInfo& f) {
    return f.noise_reached || f.spp_mean || !f.stop_reason.empty();
  };
  if (std::none_of(frames.begin(), frames.end(), says)) return;
  std::printf("%8s %14s %9s  %s\n", "frame", "noise reached", "spp mean", "stopped by");
  for (const protocol::FrameInfo& f : frames) {
    if (!says(f)) continue;
    std::printf("%8d %14s %9s  %s\n", f.frame,
                f.noise_reached ? fmt::format("{:.4g}", *f.noise_reached).c_str() : "-",
                f.spp_mean ? fmt::format("{:.1f}", *f.spp_mean).c_str() : "-",
                f.stop_reason.empty() ? "-" : escape_control_characters(f.stop_reason).c_str());
  }
}

// worker id -> name, for tables people read (escaped: names come from
// whoever holds a worker token, and an old server did not refuse ESC or CR).
std::map<std::string, std::string> worker_names(FarmClient& c) {
  std::map<std::string, std::string> names;
  for (const auto& w : c.get_json(kWorkersPath).get<protocol::WorkerList>().workers)
    names[w.worker_id] = escape_control_characters(w.name);
  return names;
}

// A failure log for a terminal: line by line, each line's control characters
// escaped (a render's stderr may carry anything).
std::string printable_log(const std::string& log) {
  std::string out;
  size_t begin = 0;
  for (size_t end; (end = log.find('\n', begin)) != std::string::npos; begin = end + 1)
    out += escape_control_characters(log.substr(begin, end - begin)) + "\n";
  return out + escape_control_characters(log.substr(begin));
}

}  // namespace

int run_status(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    if (!o.job) {
      const nlohmann::json all = c.get_json(std::string(protocol::paths::kJobs));
      if (o.json) {  // as the server said it
        std::printf("%s\n", all.dump(2).c_str());
        return 0;
      }
      const auto jobs = all.get<protocol::JobList>().jobs;
      if (jobs.empty()) std::printf("no jobs\n");
      for (const auto& j : jobs) std::printf("%s\n", describe_job(j).c_str());
      return 0;
    }
    const nlohmann::json answer = c.get_job_json(*o.job);
    if (o.json) {
      std::printf("%s\n", answer.dump(2).c_str());
      return 0;
    }
    const auto j = answer.get<protocol::JobDetail>();
    std::printf("%s\n", describe_job(j).c_str());
    const auto names = worker_names(c);
    auto name_of = [&](const std::string& id) {
      const auto it = names.find(id);
      return it == names.end() ? escape_control_characters(id) : it->second;
    };
    for (const auto& b : j.blocked_workers)
      std::printf("blocked for this job: %s\n", name_of(b).c_str());
    std::printf("%8s %6s %13s %9s %8s  %s\n", "task", "frame", "samples", "state", "attempts",
                "worker");
    for (const protocol::TaskInfo& t : j.tasks) {
      std::string state = t.state;
      if (t.progress) state += fmt::format(" {:.0f}%", 100.0 * *t.progress);
      std::printf("%8lld %6d %13s %9s %8d  %s\n", static_cast<long long>(t.id), t.frame,
                  fmt::format("[{}, {})", t.sample_begin, t.sample_end).c_str(), state.c_str(),
                  t.attempts,
                  t.reused_from ? fmt::format("(reused task {})", t.reused_from).c_str()
                                : name_of(t.worker).c_str());
    }
    print_frame_noise(j.frames);
    return 0;
  });
}

namespace {
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

int run_logs(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    const auto j = c.get_job(*o.job);
    int shown = 0;
    for (const protocol::TaskInfo& t : j.tasks) {
      if (!t.has_log) continue;
      std::printf("=== task %lld (frame %d, samples [%d, %d)), %s after %d attempts ===\n%s\n",
                  static_cast<long long>(t.id), t.frame, t.sample_begin, t.sample_end,
                  t.state.c_str(), t.attempts,
                  printable_log(c.get_text(protocol::task_log_path(*o.job, t.id))).c_str());
      ++shown;
    }
    if (shown == 0) spdlog::info("job {}: no task has a failure log", *o.job);
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
