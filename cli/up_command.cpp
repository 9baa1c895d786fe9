// vesper up: the whole farm on this machine on the embedded defaults — a local
// server (SQLite) and N workers, the demo scene submitted, a progress bar
// while it renders, the frames fetched and composited, and where it all is.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <thread>

#include "cli/commands.h"
#include "cli/farm_setup.h"
#include "cli/fetch.h"
#include "cli/job_watch.h"
#include "cli/parent_watch.h"
#include "cli/submit.h"
#include "compositor/comp_run.h"
#include "compositor/recipe.h"
#include "jobs/frame_range.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"
#include "renderer/scene/scene_loader.h"
#include "server/server.h"
#include "worker/worker.h"

namespace vesper::cli {
namespace {

std::atomic<bool> g_stop{false};
std::vector<Worker*> g_workers;  // set before the handler is installed, cleared after

extern "C" void on_up_signal(int) {
  exit_on_second_signal();
  g_stop = true;
  for (Worker* w : g_workers) w->request_stop();  // async-signal-safe (atomic flags)
}

// The demo scene: ./scenes/night-room/scene.json, else the one beside the
// build tree this binary came from (build/cli/vesper -> scenes/).
std::filesystem::path find_demo_scene() {
  const std::filesystem::path rel = "scenes/night-room/scene.json";
  if (std::filesystem::exists(rel)) return rel;
  const auto beside = self_executable().parent_path().parent_path().parent_path() / rel;
  if (std::filesystem::exists(beside)) return beside;
  throw std::runtime_error("no scene given and the demo scene " + rel.string() +
                           " is not in the current directory; pass --scene");
}

// Rewrites a composite recipe to read the fetched frames and write beside them.
CompRecipe recipe_for_frames(const std::filesystem::path& recipe_file, const FetchedFrames& frames,
                             const std::filesystem::path& out_dir, const std::string& name) {
  std::ifstream in(recipe_file);
  nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("inputs") ||
      !doc["inputs"].is_object() || doc["inputs"].size() != 1)
    throw std::runtime_error(recipe_file.string() +
                             ": /inputs: `vesper up` composites recipes with exactly one input");
  const bool sequence = frames.written.size() > 1;
  const std::filesystem::path abs_out = std::filesystem::absolute(out_dir);
  doc["inputs"].begin().value() = sequence
                                      ? std::filesystem::absolute(frames.pattern).string()
                                      : std::filesystem::absolute(frames.written.front()).string();
  const std::string stem = name + (sequence ? ".####" : "");
  nlohmann::json outputs = doc.value("outputs", nlohmann::json::object());
  const std::map<std::string, std::string> suffix = {{"image", ".comp"},
                                                     {"exr", ".comp"},
                                                     {"histogram", ".comp.hist"},
                                                     {"histogram_plot", ".comp.hist"}};
  for (const auto& [key, tail] : suffix) {
    if (!outputs.contains(key) || !outputs[key].is_string()) continue;
    const std::filesystem::path old = outputs[key].get<std::string>();
    outputs[key] = (abs_out / (stem + tail + old.extension().string())).string();
  }
  doc["outputs"] = outputs;
  return parse_recipe(doc, recipe_file.parent_path(), recipe_file.string() + " (for vesper up)");
}

}  // namespace

int run_up(const UpCommandOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  FarmSettings settings;
  JobRequest request;
  try {
    settings = load_farm_settings(o.config);
    request = job_request_defaults(settings,
                                   o.scene ? std::filesystem::path(*o.scene) : find_demo_scene());
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (o.frames) request.frames = *o.frames;
  if (o.spp) request.spp = *o.spp;
  if (o.samples_per_task) request.samples_per_task = *o.samples_per_task;
  const int n_workers = std::max(1, o.workers.value_or(settings.up.workers));
  // The workers share this machine's cores: at most `tasks` renders run at
  // once, so each gets cores / min(workers, tasks) threads. (Splitting a frame
  // over workers on one machine does not make it faster: the same cores, plus
  // each task's own scene setup and a merge — bench/farm_overhead.sh.)
  int concurrent = n_workers;
  try {
    const int frames = int(parse_frame_range(request.frames).size());
    const int spp = request.spp > 0 ? request.spp : load_scene(request.scene).render.spp;
    const int per_frame = request.samples_per_task > 0
                              ? (spp + request.samples_per_task - 1) / request.samples_per_task
                              : 1;
    concurrent = std::clamp(frames * per_frame, 1, n_workers);
  } catch (const std::exception&) {
    // Bad frames or scene: submit_job reports it properly below.
  }
  const std::filesystem::path data_dir = expand_user(o.data_dir.value_or(settings.up.data_dir));
  const std::filesystem::path out_dir = expand_user(o.output_dir.value_or(settings.up.output_dir));

  // 1. The server, on a free loopback port so `up` never collides with a farm.
  ServerConfig sc = server_config(settings);
  sc.data_dir = data_dir;
  sc.host = "127.0.0.1";
  sc.port = 0;
  std::unique_ptr<Server> server;
  try {
    server = std::make_unique<Server>(sc);
    server->start();
  } catch (const std::exception& e) {
    spdlog::error("server: {}", e.what());
    return 1;
  }
  spdlog::info("farm: {} worker{} on this machine", n_workers, n_workers == 1 ? "" : "s");

  // 2. Workers: threads here, each rendering in child processes; cores shared out.
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  export_parent_pid();  // renders and merges die with `vesper up` (parent_watch.h)
  std::vector<std::unique_ptr<Worker>> workers;
  for (int i = 0; i < n_workers; ++i) {
    WorkerConfig wc = worker_config(settings);
    wc.server_url = server->url();
    wc.token = server->worker_token();
    wc.name = fmt::format("up-{}", i + 1);
    wc.cache_dir = data_dir / "worker-cache";
    wc.idle_backoff_min = 0.05;  // one machine: poll eagerly
    wc.idle_backoff_max = 0.5;
    wc.render_threads = std::max(1, cores / concurrent);
    workers.push_back(std::make_unique<Worker>(wc));
  }
  for (auto& w : workers) g_workers.push_back(w.get());
  on_stop_signals(on_up_signal);
  // Worker chatter would break the progress bar; their warnings still show.
  const auto level = spdlog::get_level();
  spdlog::set_level(std::max(level, spdlog::level::warn));
  std::vector<std::thread> threads;
  for (auto& w : workers) threads.emplace_back([&w] { w->run(); });
  auto stop_all = [&] {
    for (auto& w : workers) w->request_stop();
    for (auto& t : threads) t.join();
    threads.clear();
    g_workers.clear();
    // Their keep-alive connections close with them; otherwise the server's stop
    // waits out the keep-alive timeout.
    workers.clear();
    spdlog::set_level(level);
  };

  // 3. Submit, wait, fetch.
  int rc = 0;
  FetchedFrames fetched;
  protocol::JobDetail final_state;
  try {
    FarmClient client(server->url(), server->submitter_token());
    // An interrupted earlier `vesper up` may have left unfinished jobs here:
    // they would take the workers first. Its finished work stays (and is
    // reused where the inputs are the same).
    const auto previous =
        client.get_json(std::string(protocol::paths::kJobs)).get<protocol::JobList>();
    for (const protocol::JobSummary& j : previous.jobs)
      if (!j.finished && j.state != "canceled") {
        client.post_json(protocol::job_action_path(j.id, protocol::JobAction::Cancel),
                         nlohmann::json::object());
        spdlog::warn("canceled job {} '{}' left unfinished by an earlier `vesper up` in {}", j.id,
                     j.name, data_dir.string());
      }
    const Submitted s = submit_job(client, request);
    spdlog::set_level(level);
    spdlog::info("submitted job {} '{}': frames {}, {} tasks", s.id, request.name, request.frames,
                 s.task_count);
    spdlog::set_level(std::max(level, spdlog::level::warn));
    final_state = wait_for_job(client, s.id, true, [] { return g_stop.load(); });
    stop_all();
    if (g_stop) {
      spdlog::warn(
          "interrupted: {}; kept in {} (`vesper server --data-dir {}` serves it, "
          "`vesper fetch` gets its frames)",
          describe_job(client.get_json(protocol::job_path(s.id)).get<protocol::JobDetail>()),
          data_dir.string(), data_dir.string());
      return 130;
    }
    spdlog::info("{}", describe_job(final_state));
    fetched = fetch_frames(client, s.id, out_dir);
    if (!fetched.missing.empty()) rc = 3;
  } catch (const std::exception& e) {
    if (!g_workers.empty()) stop_all();
    spdlog::error("{}", e.what());
    return dynamic_cast<const SceneError*>(&e) ? 2 : 1;
  }
  server->stop();

  // 4. Composite with the scene's recipe (comp.json beside it), if any.
  std::vector<std::filesystem::path> comp_outputs;
  const std::filesystem::path recipe =
      o.comp ? std::filesystem::path(*o.comp) : request.scene.parent_path() / "comp.json";
  if (!o.no_comp && !fetched.written.empty() && std::filesystem::exists(recipe)) {
    try {
      const CompRecipe r = recipe_for_frames(recipe, fetched, out_dir, request.name);
      const CompReport report = run_comp(r);
      for (const auto& f : report.frames)
        for (const auto& p : {f.image, f.exr, f.histogram, f.histogram_plot})
          if (!p.empty()) comp_outputs.push_back(p);
    } catch (const std::exception& e) {
      spdlog::error("composite: {}", e.what());
      rc = 1;
    }
  }

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "\nvesper up: %d worker%s, %.1f s\n", n_workers, n_workers == 1 ? "" : "s",
               seconds);
  std::fprintf(stderr, "  frames:     %zu in %s\n", fetched.written.size(),
               std::filesystem::path(fetched.pattern).parent_path().string().c_str());
  for (const auto& p : fetched.written) std::printf("%s\n", p.string().c_str());
  for (const auto& p : comp_outputs) std::printf("%s\n", p.string().c_str());
  if (!comp_outputs.empty())
    std::fprintf(stderr, "  composite:  %zu files (image, EXR, histogram JSON + plot)\n",
                 comp_outputs.size());
  std::fprintf(stderr, "  farm data:  %s (jobs.sqlite, blobs/, tokens.json)\n",
               data_dir.string().c_str());
  return rc;
}

}  // namespace vesper::cli
