#include "server/job_webhook.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "protocol/fields.h"
#include "server/locked_store.h"
#include "worker/http_client.h"

namespace vesper {

nlohmann::json webhook_payload(const JobStore::EndedJob& ended) {
  namespace f = protocol::field;
  const JobSummary& j = ended.job;
  nlohmann::json out = {{f::kId, j.id},
                        {f::kName, j.name},
                        {f::kState, to_string(j.state)},
                        {f::kSubmitted, j.submitted_at},
                        {f::kFrames, ended.frames},
                        {"failed_tasks", j.failed}};
  if (j.started_at) out[f::kStarted] = *j.started_at;
  if (j.finished_at) out[f::kFinished] = *j.finished_at;
  return out;
}

JobWebhook::JobWebhook(WebhookOptions options, LockedStore& store)
    : options_(std::move(options)), store_(store) {}

JobWebhook::~JobWebhook() { stop(); }

void JobWebhook::start() {
  thread_ = std::thread([this] { run(); });
}

void JobWebhook::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void JobWebhook::wake() {
  {
    std::lock_guard lock(mutex_);
    woken_ = true;
  }
  cv_.notify_all();
}

bool JobWebhook::wait(double seconds, bool until_woken) {
  std::unique_lock lock(mutex_);
  cv_.wait_for(lock, std::chrono::duration<double>(seconds),
               [&] { return stopping_ || (until_woken && woken_); });
  if (until_woken) woken_ = false;
  return !stopping_;
}

void JobWebhook::run() {
  do {
    std::vector<JobStore::EndedJob> ended;
    try {
      ended = store_.read([](const JobStore& s) { return s.jobs_to_announce(); });
    } catch (const std::exception& e) {
      spdlog::warn("webhook: cannot read the ended jobs: {}", e.what());
    }
    for (const JobStore::EndedJob& e : ended) announce(e);
  } while (wait(options_.poll_seconds, true));
}

void JobWebhook::announce(const JobStore::EndedJob& ended) {
  const int64_t id = ended.job.id;
  const std::string body = webhook_payload(ended).dump();
  worker_detail::HttpClient http(options_.url, "", options_.timeout_seconds);
  double delay = options_.retry_seconds;
  for (int attempt = 1; attempt <= options_.attempts; ++attempt) {
    const worker_detail::HttpResponse r = http.post_json("", body);
    if (r.ok()) {
      spdlog::info("webhook: job {} {} announced", id, to_string(ended.job.state));
      break;
    }
    const std::string why = r.status == 0 ? r.error : "HTTP " + std::to_string(r.status);
    if (attempt == options_.attempts) {
      spdlog::error("webhook: job {} not announced to {} after {} attempts ({}); given up", id,
                    options_.url, attempt, why);
      break;
    }
    spdlog::warn("webhook: POST {} for job {} failed ({}); retrying in {} s", options_.url, id, why,
                 delay);
    if (!wait(delay, false)) return;  // stopping: announced at the next start
    delay *= 2;
  }
  store_.with([&](JobStore& s) { s.mark_announced(id); });
}

}  // namespace vesper
