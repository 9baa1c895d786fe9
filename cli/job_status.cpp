// vesper status [JOB]: the farm's jobs (state, tasks, times, ETA), or one
// job with its tasks (state, attempts, worker, duration) and frames.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <map>

#include "cli/job_client.h"
#include "cli/job_watch.h"
#include "cli/progress.h"
#include "common/control_characters.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"

namespace vesper::cli {
namespace {

// The server's clock (seconds since the Unix epoch) in local time; "-" when unset.
std::string format_time(std::optional<double> t, const char* format = "%m-%d %H:%M:%S") {
  if (!t) return "-";
  const std::time_t s = std::time_t(*t);
  std::tm tm{};
  localtime_r(&s, &tm);
  char buf[32];
  return std::strftime(buf, sizeof buf, format, &tm) > 0 ? buf : "-";
}

// As the progress bar writes times (format_seconds); "-" when unset.
std::string format_duration(std::optional<double> seconds) {
  return seconds ? format_seconds(std::max(0.0, *seconds)) : "-";
}

// A job's wall time: start to finish, or to `now` while it has not ended.
std::optional<double> job_duration(const protocol::JobSummary& j, double now) {
  if (!j.started) return std::nullopt;
  if (j.finished) return *j.finished - *j.started;
  return j.ended() ? std::nullopt : std::optional<double>(now - *j.started);
}

void print_job_table(const std::vector<protocol::JobSummary>& jobs, double now) {
  std::printf("%6s  %-9s %11s  %-14s  %-14s  %-14s  %9s  %9s  %s\n", "job", "state", "tasks done",
              "submitted", "started", "finished", "duration", "eta", "name");
  for (const protocol::JobSummary& j : jobs)
    std::printf("%6lld  %-9s %11s  %-14s  %-14s  %-14s  %9s  %9s  %s\n",
                static_cast<long long>(j.id), j.state.c_str(),
                fmt::format("{}/{}", j.counts.done, j.total).c_str(),
                format_time(j.submitted).c_str(), format_time(j.started).c_str(),
                format_time(j.finished).c_str(), format_duration(job_duration(j, now)).c_str(),
                format_duration(j.eta).c_str(), escape_control_characters(j.name).c_str());
}

void print_job_times(const protocol::JobSummary& j, double now) {
  const char* full = "%Y-%m-%d %H:%M:%S";
  std::string line = "submitted " + format_time(j.submitted, full);
  if (j.started) line += ", started " + format_time(j.started, full);
  if (j.finished) line += ", finished " + format_time(j.finished, full);
  if (const auto d = job_duration(j, now))
    line += (j.finished ? ", took " : ", running for ") + format_duration(d);
  if (j.eta) line += ", about " + format_duration(j.eta) + " left";
  std::printf("%s\n", line.c_str());
}

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

}  // namespace

std::map<std::string, std::string> worker_names(FarmClient& c) {
  std::map<std::string, std::string> names;
  for (const auto& w :
       c.get_json(std::string(protocol::paths::kWorkers)).get<protocol::WorkerList>().workers)
    names[w.worker_id] = escape_control_characters(w.name);
  return names;
}

namespace {

// How long a task's last attempt took, or has run so far ("+": still running).
std::string task_duration(const protocol::TaskInfo& t, double now) {
  if (t.duration) return format_duration(t.duration);
  if (t.state == "leased" && t.started) return format_duration(now - *t.started) + "+";
  return "-";
}

void print_task_table(const protocol::JobDetail& j,
                      const std::map<std::string, std::string>& names) {
  auto name_of = [&](const std::string& id) {
    const auto it = names.find(id);
    return it == names.end() ? escape_control_characters(id) : it->second;
  };
  std::printf("%8s %6s %13s %9s %8s %9s  %s\n", "task", "frame", "samples", "state", "attempts",
              "duration", "worker");
  for (const protocol::TaskInfo& t : j.tasks) {
    std::string state = t.state;
    if (t.progress) state += fmt::format(" {:.0f}%", 100.0 * *t.progress);
    std::printf("%8lld %6d %13s %9s %8d %9s  %s\n", static_cast<long long>(t.id), t.frame,
                fmt::format("[{}, {})", t.sample_begin, t.sample_end).c_str(), state.c_str(),
                t.attempts, task_duration(t, j.now).c_str(),
                t.reused_from ? fmt::format("(reused task {})", t.reused_from).c_str()
                              : name_of(t.worker).c_str());
  }
}

int print_job_list(FarmClient& c, bool json) {
  const nlohmann::json all = c.get_json(std::string(protocol::paths::kJobs));
  if (json) {  // as the server said it
    std::printf("%s\n", all.dump(2).c_str());
    return 0;
  }
  const auto list = all.get<protocol::JobList>();
  if (list.jobs.empty())
    std::printf("no jobs\n");
  else
    print_job_table(list.jobs, list.now);
  return 0;
}

}  // namespace

int run_status(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    if (!o.job) return print_job_list(c, o.json);
    const nlohmann::json answer = c.get_job_json(*o.job);
    if (o.json) {
      std::printf("%s\n", answer.dump(2).c_str());
      return 0;
    }
    const auto j = answer.get<protocol::JobDetail>();
    std::printf("%s\n", describe_job(j).c_str());
    print_job_times(j.summary, j.now);
    const auto names = worker_names(c);
    for (const auto& b : j.blocked_workers) {
      const auto it = names.find(b);
      std::printf("blocked for this job: %s\n",
                  it == names.end() ? escape_control_characters(b).c_str() : it->second.c_str());
    }
    print_task_table(j, names);
    print_frame_noise(j.frames);
    return 0;
  });
}

}  // namespace vesper::cli
