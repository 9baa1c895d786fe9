#include "cli/regress_farm.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>

#include "cli/fetch.h"
#include "cli/job_watch.h"
#include "cli/submit.h"
#include "common/utf8.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"

namespace vesper::cli {
namespace {

namespace fs = std::filesystem;

// A suite scene as a farm job: the render --local runs, as job settings.
JobRequest scene_job(const regress::SuiteScene& s, const FarmBatchSettings& settings) {
  JobRequest r;
  r.scene = s.scene;
  r.name = "regress " + s.name;
  r.frames = s.frames;
  r.spp = s.spp.value_or(0);  // 0: the scene's render.spp (the most, with a noise target)
  r.sampling.budget.noise_target = s.noise_target;
  r.overrides = suite_render_overrides(s, settings.seed);
  return r;
}

// The suite's scenes as jobs; a scene that cannot be submitted keeps why.
struct SceneJob {
  int64_t id = 0;  // 0: not submitted
  std::string error;
  protocol::JobDetail detail;
  std::vector<protocol::FrameInfo> frames;
};

std::map<const regress::SuiteScene*, SceneJob> submit_suite(FarmClient& client,
                                                            const regress::Suite& suite,
                                                            const FarmBatchSettings& settings) {
  std::map<const regress::SuiteScene*, SceneJob> jobs;
  for (const regress::SuiteScene& s : suite.scenes) {
    SceneJob& job = jobs[&s];
    try {
      const Submitted submitted = submit_job(client, scene_job(s, settings));
      job.id = submitted.id;
      spdlog::info("{}: farm job {} ({} tasks)", s.name, job.id, submitted.task_count);
    } catch (const std::exception& e) {  // a scene the loader or the server refuses
      job.error = "not submitted to the farm: " + std::string(e.what());
    }
  }
  return jobs;
}

// The last lines of a failed task's log (the worker's account of the render
// and its stderr tail), on one line: a reason is one line in every output.
std::string log_tail(FarmClient& client, int64_t job, int64_t task) {
  std::string log;
  try {
    log = client.get_text(protocol::task_log_path(job, task));
  } catch (const FarmClientError& e) {
    return std::string("its log could not be read: ") + e.what();
  }
  std::vector<std::string> lines;
  for (size_t begin = 0; begin < log.size();) {
    size_t end = log.find('\n', begin);
    if (end == std::string::npos) end = log.size();
    if (log.find_first_not_of(" \t\r", begin) < end)
      lines.push_back(log.substr(begin, end - begin));
    begin = end + 1;
  }
  std::string tail;
  for (size_t i = lines.size() > 6 ? lines.size() - 6 : 0; i < lines.size(); ++i)
    tail += (tail.empty() ? "" : " | ") + lines[i];
  if (tail.size() > 800) tail = "..." + utf8_tail(tail, 800);  // a log may hold any bytes
  return tail.empty() ? "no log" : "its log ends: " + tail;
}

// Why frame `frame` of `job` has no output.
std::string frame_failure(FarmClient& client, const SceneJob& job, int frame) {
  for (const protocol::TaskInfo& t : job.detail.tasks)
    if (t.frame == frame && t.state == "failed")
      return fmt::format("farm task {} of job {} (frame {}) failed after {} attempts; {}", t.id,
                         job.id, frame, t.attempts, log_tail(client, job.id, t.id));
  if (job.detail.summary.state == "canceled")
    return fmt::format("farm job {} was canceled before frame {} was rendered", job.id, frame);
  for (const protocol::FrameInfo& f : job.frames)
    if (f.frame == frame && !f.error.empty())
      return fmt::format("frame {} of farm job {}: {}", frame, job.id, f.error);
  return fmt::format("frame {} of farm job {} was not rendered ({})", frame, job.id,
                     describe_job(job.detail.summary));
}

// Every task of the frame took the result of an identical earlier one.
bool frame_reused(const protocol::JobDetail& job, int frame) {
  int tasks = 0, reused = 0;
  for (const protocol::TaskInfo& t : job.tasks)
    if (t.frame == frame) ++tasks, reused += t.reused_from != 0;
  return tasks > 0 && reused == tasks;
}

// The frame's output, fetched, with its render time and whether it was reused.
SuiteRender fetch_frame(FarmClient& client, const SceneJob& job, const SuiteFrame& f,
                        const fs::path& out_dir) {
  SuiteRender r;
  r.label = f.label;
  r.on_farm = true;
  r.exr = out_dir / (f.label + ".exr");
  const auto info = std::find_if(job.frames.begin(), job.frames.end(),
                                 [&](const protocol::FrameInfo& i) { return i.frame == f.frame; });
  if (info == job.frames.end() || info->state != protocol::FrameState::Ready) {
    r.error = frame_failure(client, job, f.frame);
    return r;
  }
  try {
    download_frame(client, job.id, *info, r.exr);
    if (const auto seconds = exr_render_seconds(r.exr)) r.seconds.push_back(*seconds);
  } catch (const std::exception& e) {
    r.error =
        fmt::format("frame {} of farm job {} could not be fetched: {}", f.frame, job.id, e.what());
  }
  r.reused = frame_reused(job.detail, f.frame);
  return r;
}

}  // namespace

std::vector<SuiteRender> render_suite_on_farm(FarmClient& client, const regress::Suite& suite,
                                              const std::vector<SuiteFrame>& frames,
                                              const FarmBatchSettings& settings) {
  std::map<const regress::SuiteScene*, SceneJob> jobs = submit_suite(client, suite, settings);
  std::vector<int64_t> ids;
  for (const auto& [scene, job] : jobs)
    if (job.id != 0) ids.push_back(job.id);
  if (client.get_json(std::string(protocol::paths::kWorkers))
          .get<protocol::WorkerList>()
          .workers.empty())
    spdlog::warn("no worker is registered at {}: waiting for one", client.url());
  const std::vector<protocol::JobDetail> done =
      wait_for_jobs(client, ids, "regress", settings.show_progress);
  for (auto& [scene, job] : jobs) {
    if (job.id == 0) continue;
    job.detail = *std::find_if(done.begin(), done.end(), [&](const protocol::JobDetail& d) {
      return d.summary.id == job.id;
    });
    job.frames = wait_for_merges(client, job.id).frames;
  }
  std::vector<SuiteRender> out;
  for (const SuiteFrame& f : frames) {
    const SceneJob& job = jobs.at(f.scene);
    if (job.id != 0) {
      out.push_back(fetch_frame(client, job, f, settings.out_dir));
      continue;
    }
    SuiteRender unsent;
    unsent.label = f.label;
    unsent.error = job.error;
    unsent.on_farm = true;
    out.push_back(std::move(unsent));
  }
  return out;
}

}  // namespace vesper::cli
