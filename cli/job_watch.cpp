#include "cli/job_watch.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <thread>

#include "cli/progress.h"
#include "common/control_characters.h"
#include "protocol/paths.h"

namespace vesper::cli {

std::string describe_job(const protocol::JobSummary& j) {
  const protocol::JobCounts& c = j.counts;
  std::string s = "job " + std::to_string(j.id) + " '" + escape_control_characters(j.name) +
                  "': " + j.state + ", " + std::to_string(c.done) + "/" + std::to_string(j.total) +
                  " tasks done";
  const std::pair<int, const char*> others[] = {{c.leased, "leased"},
                                                {c.queued, "queued"},
                                                {c.failed, "failed"},
                                                {c.paused, "paused"},
                                                {c.canceled, "canceled"}};
  for (const auto& [count, what] : others)
    if (count > 0) s += ", " + std::to_string(count) + " " + what;
  return s;
}

std::string describe_job(const protocol::JobDetail& j) {
  std::string s = describe_job(j.summary);
  const auto reused = std::count_if(j.tasks.begin(), j.tasks.end(),
                                    [](const protocol::TaskInfo& t) { return t.reused_from != 0; });
  if (reused > 0)
    s += " (" + std::to_string(reused) +
         " reused from identical tasks done before, not rendered again)";
  return s + describe_noise(j.frames);
}

std::string describe_noise(const std::vector<protocol::FrameInfo>& frames) {
  double worst = 0, spp_sum = 0;
  int with_noise = 0, with_spp = 0;
  for (const protocol::FrameInfo& f : frames) {
    if (f.noise_reached) worst = std::max(worst, *f.noise_reached), ++with_noise;
    if (f.spp_mean) spp_sum += *f.spp_mean, ++with_spp;
  }
  std::string s;
  if (with_noise > 0)
    s += fmt::format("; noise reached {:.4g} (the worst of {} frame{})", worst, with_noise,
                     with_noise == 1 ? "" : "s");
  if (with_spp > 0) s += fmt::format("; {:.1f} spp on average", spp_sum / with_spp);
  return s;
}

namespace {

bool all_workers_blocked(FarmClient& client, const protocol::JobDetail& job) {
  const std::set<std::string> blocked(job.blocked_workers.begin(), job.blocked_workers.end());
  const auto all =
      client.get_json(std::string(protocol::paths::kWorkers)).get<protocol::WorkerList>();
  for (const protocol::WorkerInfo& w : all.workers)
    if (!blocked.count(w.worker_id)) return false;
  return true;
}

// Settled tasks plus the running ones' heartbeat progress.
double tasks_settled(const protocol::JobDetail& j) {
  const protocol::JobCounts& c = j.summary.counts;
  double settled = c.done + c.failed + c.canceled;
  for (const protocol::TaskInfo& t : j.tasks)
    if (t.progress) settled += std::clamp(*t.progress, 0.0, 1.0);
  return settled;
}

void report_failed_tasks(const protocol::JobDetail& j, std::set<int64_t>& reported) {
  for (const protocol::TaskInfo& t : j.tasks)
    if (t.state == "failed" && reported.insert(t.id).second)
      spdlog::error(
          "job {}: task {} (frame {}, samples [{}, {})) failed after {} attempts; "
          "`vesper logs {}` shows why",
          j.summary.id, t.id, t.frame, t.sample_begin, t.sample_end, t.attempts, j.summary.id);
}

}  // namespace

protocol::FrameList wait_for_merges(FarmClient& client, int64_t job) {
  protocol::FrameList frames;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  for (;;) {
    frames = client.get_json(protocol::frames_path(job)).get<protocol::FrameList>();
    bool merging = false;
    for (const protocol::FrameInfo& f : frames.frames)
      merging = merging || (f.state == protocol::FrameState::Pending && f.done == f.tasks);
    if (!merging || std::chrono::steady_clock::now() > deadline) return frames;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

namespace {

// Whether waiting for `j` is over: finished, canceled, or left with queued
// work no registered worker may take (each is blocklisted for this job),
// which would be waited for forever (said as an error).
bool wait_is_over(FarmClient& client, const protocol::JobDetail& j) {
  if (j.summary.ended()) return true;
  const protocol::JobCounts& c = j.summary.counts;
  if (c.queued == 0 || c.leased > 0 || j.blocked_workers.empty() || !all_workers_blocked(client, j))
    return false;
  spdlog::error(
      "job {}: every registered worker is blocklisted for this job after failing "
      "its tasks, so its {} queued tasks will not run; see `vesper logs {}`, fix "
      "the cause, then `vesper retry {}`",
      j.summary.id, c.queued, j.summary.id, j.summary.id);
  return true;
}

}  // namespace

std::vector<protocol::JobDetail> wait_for_jobs(FarmClient& client, const std::vector<int64_t>& jobs,
                                               const std::string& label, bool show_progress,
                                               const std::function<bool()>& should_stop) {
  Progress progress(label);
  std::set<int64_t> reported;
  std::vector<protocol::JobDetail> last(jobs.size());
  std::vector<bool> over(jobs.size(), false);
  auto delay = std::chrono::milliseconds(100);
  for (;;) {
    try {
      for (size_t i = 0; i < jobs.size(); ++i) {
        if (over[i]) continue;
        last[i] = client.get_job(jobs[i]);
        report_failed_tasks(last[i], reported);
        over[i] = wait_is_over(client, last[i]);
      }
    } catch (const FarmClientError& e) {
      // The server may be restarting: keep waiting, but say so.
      spdlog::warn("{} (retrying)", e.what());
      std::this_thread::sleep_for(std::chrono::seconds(1));
      continue;
    }
    double settled = 0;
    size_t total = 0;
    for (const protocol::JobDetail& j : last) settled += tasks_settled(j), total += j.summary.total;
    // In thousandths, so that running tasks move the bar.
    if (show_progress && total > 0) progress.update(size_t(settled * 1000), total * 1000);
    if (std::all_of(over.begin(), over.end(), [](bool b) { return b; }) ||
        (should_stop && should_stop())) {
      if (show_progress) progress.finish();
      return last;
    }
    std::this_thread::sleep_for(delay);
    delay = std::min(delay * 2, std::chrono::milliseconds(500));
  }
}

protocol::JobDetail wait_for_job(FarmClient& client, int64_t job, bool show_progress,
                                 const std::function<bool()>& should_stop) {
  return wait_for_jobs(client, {job}, "job " + std::to_string(job), show_progress, should_stop)
      .front();
}

}  // namespace vesper::cli
