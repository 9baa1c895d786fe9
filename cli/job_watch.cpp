#include "cli/job_watch.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <thread>

#include "cli/progress.h"

namespace vesper::cli {

std::string describe_job(const nlohmann::json& j) {
  const auto& c = j.at("counts");
  std::string s = "job " + std::to_string(j.at("id").get<long long>()) + " '" +
                  j.at("name").get<std::string>() + "': " + j.at("state").get<std::string>() +
                  ", " + std::to_string(c.at("done").get<int>()) + "/" +
                  std::to_string(j.at("total").get<int>()) + " tasks done";
  for (const char* k : {"leased", "queued", "failed", "paused", "canceled"})
    if (c.at(k).get<int>() > 0) s += ", " + std::to_string(c.at(k).get<int>()) + " " + k;
  int reused = 0;
  for (const auto& t : j.value("tasks", nlohmann::json::array()))
    reused += t.contains("reused_from");
  if (reused > 0)
    s += " (" + std::to_string(reused) +
         " reused from identical tasks done before, not rendered again)";
  return s;
}

namespace {
bool all_workers_blocked(FarmClient& client, const nlohmann::json& job) {
  std::set<std::string> blocked;
  for (const auto& b : job.at("blocked_workers")) blocked.insert(b.get<std::string>());
  const nlohmann::json all = client.get_json("/workers");
  for (const auto& w : all.at("workers"))
    if (!blocked.count(w.at("worker_id").get<std::string>())) return false;
  return true;
}
}  // namespace

nlohmann::json wait_for_job(FarmClient& client, long long job, bool show_progress,
                            const std::function<bool()>& should_stop) {
  const std::string path = "/jobs/" + std::to_string(job);
  Progress progress("job " + std::to_string(job));
  std::set<long long> reported;
  auto delay = std::chrono::milliseconds(100);
  for (;;) {
    nlohmann::json j;
    try {
      j = client.get_json(path);
    } catch (const FarmClientError& e) {
      // The server may be restarting: keep waiting, but say so.
      spdlog::warn("{} (retrying)", e.what());
      std::this_thread::sleep_for(std::chrono::seconds(1));
      continue;
    }
    for (const auto& t : j.value("tasks", nlohmann::json::array()))
      if (t.at("state") == "failed" && reported.insert(t.at("id").get<long long>()).second)
        spdlog::error(
            "job {}: task {} (frame {}, samples [{}, {})) failed after {} attempts; "
            "`vesper logs {}` shows why",
            job, t.at("id").get<long long>(), t.at("frame").get<int>(),
            t.at("sample_begin").get<int>(), t.at("sample_end").get<int>(),
            t.at("attempts").get<int>(), job);
    const int total = j.at("total").get<int>();
    const auto& c = j.at("counts");
    // Settled tasks plus the running ones' heartbeat progress, in thousandths.
    double settled =
        c.at("done").get<int>() + c.at("failed").get<int>() + c.at("canceled").get<int>();
    for (const auto& t : j.value("tasks", nlohmann::json::array()))
      if (t.contains("progress")) settled += std::clamp(t.at("progress").get<double>(), 0.0, 1.0);
    if (show_progress && total > 0) progress.update(size_t(settled * 1000), size_t(total) * 1000);
    if (j.at("finished").get<bool>() || j.at("state") == "canceled" ||
        (should_stop && should_stop())) {
      if (show_progress) progress.finish();
      return j;
    }
    // Queued work no registered worker may take (each is blocklisted for this
    // job) would be waited for forever: say so and stop waiting.
    if (c.at("queued").get<int>() > 0 && c.at("leased").get<int>() == 0 &&
        !j.value("blocked_workers", nlohmann::json::array()).empty() &&
        all_workers_blocked(client, j)) {
      if (show_progress) progress.finish();
      spdlog::error(
          "job {}: every registered worker is blocklisted for this job after failing "
          "its tasks, so its {} queued tasks will not run; see `vesper logs {}`, fix "
          "the cause, then `vesper retry {}`",
          job, c.at("queued").get<int>(), job, job);
      return j;
    }
    std::this_thread::sleep_for(delay);
    delay = std::min(delay * 2, std::chrono::milliseconds(500));
  }
}

}  // namespace vesper::cli
