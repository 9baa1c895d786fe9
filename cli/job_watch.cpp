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
    const int settled =
        c.at("done").get<int>() + c.at("failed").get<int>() + c.at("canceled").get<int>();
    if (show_progress && total > 0) progress.update(size_t(settled), size_t(total));
    if (j.at("finished").get<bool>() || j.at("state") == "canceled" ||
        (should_stop && should_stop())) {
      if (show_progress) progress.finish();
      return j;
    }
    std::this_thread::sleep_for(delay);
    delay = std::min(delay * 2, std::chrono::milliseconds(500));
  }
}

}  // namespace vesper::cli
