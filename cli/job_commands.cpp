// vesper status | cancel | retry | logs | fetch: a job on the farm.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "cli/commands.h"
#include "cli/fetch.h"
#include "cli/job_watch.h"
#include "common/sha256.h"

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

std::string job_path(const JobCommandOptions& o) { return "/jobs/" + std::to_string(*o.job); }

// worker id -> name, for tables people read.
std::map<std::string, std::string> worker_names(FarmClient& c) {
  std::map<std::string, std::string> names;
  const nlohmann::json all = c.get_json("/workers");  // not a temporary in the range-for
  for (const auto& w : all.at("workers"))
    names[w.at("worker_id").get<std::string>()] = w.at("name").get<std::string>();
  return names;
}

}  // namespace

FetchedFrames fetch_frames(FarmClient& client, long long job, const std::filesystem::path& dir) {
  const std::string base = "/jobs/" + std::to_string(job);
  const nlohmann::json j = client.get_json(base);
  // Frames whose tasks are all done may still be merging on the server: give
  // the merges time (a merge reads and writes the frame once; seconds).
  nlohmann::json frames;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  for (;;) {
    frames = client.get_json(base + "/frames");
    bool merging = false;
    for (const auto& f : frames.at("frames"))
      merging = merging || (f.at("state") == "pending" && f.at("done") == f.at("tasks"));
    if (!merging || std::chrono::steady_clock::now() > deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  std::filesystem::create_directories(dir);
  FetchedFrames out;
  const std::string name = j.at("name").get<std::string>();
  out.pattern = (dir / (name + ".####.exr")).string();
  for (const auto& f : frames.at("frames")) {
    const int frame = f.at("frame").get<int>();
    if (f.at("state") != "ready") {
      out.missing.push_back(frame);
      continue;
    }
    const std::filesystem::path file = dir / fmt::format("{}.{:04d}.exr", name, frame);
    client.download(base + "/frames/" + std::to_string(frame), file);
    if (f.contains("blob")) {
      const auto sha = sha256_file(file);
      if (!sha || *sha != f.at("blob").get<std::string>()) {
        std::filesystem::remove(file);
        throw FarmClientError(file.string() + ": downloaded frame does not match its hash");
      }
    }
    out.written.push_back(file);
  }
  return out;
}

int run_status(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    if (!o.job) {
      const nlohmann::json all = c.get_json("/jobs");
      if (o.json) {
        std::printf("%s\n", all.dump(2).c_str());
        return 0;
      }
      if (all.at("jobs").empty()) std::printf("no jobs\n");
      for (const auto& j : all.at("jobs")) std::printf("%s\n", describe_job(j).c_str());
      return 0;
    }
    const nlohmann::json j = c.get_json(job_path(o));
    if (o.json) {
      std::printf("%s\n", j.dump(2).c_str());
      return 0;
    }
    std::printf("%s\n", describe_job(j).c_str());
    const auto names = worker_names(c);
    auto name_of = [&](const std::string& id) {
      const auto it = names.find(id);
      return it == names.end() ? id : it->second;
    };
    for (const auto& b : j.value("blocked_workers", nlohmann::json::array()))
      std::printf("blocked for this job: %s\n", name_of(b.get<std::string>()).c_str());
    std::printf("%8s %6s %13s %9s %8s  %s\n", "task", "frame", "samples", "state", "attempts",
                "worker");
    for (const auto& t : j.at("tasks")) {
      std::string state = t.at("state").get<std::string>();
      if (t.contains("progress"))
        state += fmt::format(" {:.0f}%", 100.0 * t.at("progress").get<double>());
      std::printf(
          "%8lld %6d %13s %9s %8d  %s\n", t.at("id").get<long long>(), t.at("frame").get<int>(),
          fmt::format("[{}, {})", t.at("sample_begin").get<int>(), t.at("sample_end").get<int>())
              .c_str(),
          state.c_str(), t.at("attempts").get<int>(),
          t.contains("reused_from")
              ? fmt::format("(reused task {})", t.at("reused_from").get<long long>()).c_str()
              : name_of(t.at("worker").get<std::string>()).c_str());
    }
    return 0;
  });
}

namespace {
int job_action(const JobCommandOptions& o, const char* action, const char* done) {
  return with_client(o, [&](FarmClient& c) {
    const nlohmann::json a = c.post_json(job_path(o) + "/" + action, nlohmann::json::object());
    spdlog::info("{}: {}", done, describe_job(a.at("job")));
    return 0;
  });
}

}  // namespace

int run_cancel(const JobCommandOptions& o) { return job_action(o, "cancel", "canceled"); }
int run_pause(const JobCommandOptions& o) { return job_action(o, "pause", "paused"); }
int run_resume(const JobCommandOptions& o) { return job_action(o, "resume", "resumed"); }

int run_workers(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    const nlohmann::json all = c.get_json("/workers");
    if (o.json) {
      std::printf("%s\n", all.dump(2).c_str());
      return 0;
    }
    const double now = all.value("now", 0.0);
    if (all.at("workers").empty())
      std::printf("no workers\n");
    else
      std::printf("%-24s %-34s %12s %7s\n", "name", "worker id", "last seen", "leases");
    for (const auto& w : all.at("workers"))
      std::printf("%-24s %-34s %10.0fs ago %7s\n", w.at("name").get<std::string>().c_str(),
                  w.at("worker_id").get<std::string>().c_str(),
                  now - w.at("last_seen").get<double>(), w.at("leases").dump().c_str());
    return 0;
  });
}

int run_retry(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    const nlohmann::json a = c.post_json(job_path(o) + "/retry-failed", nlohmann::json::object());
    spdlog::info("requeued {} failed tasks: {}", a.value("requeued", 0), describe_job(a.at("job")));
    return 0;
  });
}

int run_logs(const JobCommandOptions& o) {
  return with_client(o, [&](FarmClient& c) {
    const nlohmann::json j = c.get_json(job_path(o));
    int shown = 0;
    for (const auto& t : j.at("tasks")) {
      if (!t.value("has_log", false)) continue;
      const long long id = t.at("id").get<long long>();
      std::printf("=== task %lld (frame %d, samples [%d, %d)), %s after %d attempts ===\n%s\n", id,
                  t.at("frame").get<int>(), t.at("sample_begin").get<int>(),
                  t.at("sample_end").get<int>(), t.at("state").get<std::string>().c_str(),
                  t.at("attempts").get<int>(),
                  c.get_text(job_path(o) + "/tasks/" + std::to_string(id) + "/log").c_str());
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
      std::string list;
      for (int m : f.missing) list += (list.empty() ? "" : ",") + std::to_string(m);
      spdlog::warn("job {}: frames not ready (pending or failed): {}", *o.job, list);
      return 3;
    }
    return 0;
  });
}

}  // namespace vesper::cli
