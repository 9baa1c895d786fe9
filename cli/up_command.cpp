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
#include "common/control_characters.h"
#include "common/json_parse.h"
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
                             const std::filesystem::path& out_dir) {
  nlohmann::json doc = read_json_file(recipe_file, "the composite recipe");
  if (!doc.is_object() || !doc.contains("inputs") || !doc["inputs"].is_object() ||
      doc["inputs"].size() != 1)
    throw std::runtime_error(recipe_file.string() +
                             ": /inputs: `vesper up` composites recipes with exactly one input");
  const bool sequence = frames.written.size() > 1;
  const std::filesystem::path abs_out = std::filesystem::absolute(out_dir);
  doc["inputs"].begin().value() = sequence
                                      ? std::filesystem::absolute(frames.pattern).string()
                                      : std::filesystem::absolute(frames.written.front()).string();
  const std::string stem = frames.stem + (sequence ? ".####" : "");
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

// What `vesper up` will run: settings, the job, and how the cores are shared.
struct UpPlan {
  FarmSettings settings;
  JobRequest request;
  int workers = 1;
  int threads_per_render = 1;
  std::filesystem::path data_dir, out_dir;
};

// Throws on bad settings or a missing scene (a usage error).
UpPlan plan_up(const UpCommandOptions& o) {
  UpPlan p;
  p.settings = load_farm_settings(o.config);
  p.request = job_request_defaults(p.settings,
                                   o.scene ? std::filesystem::path(*o.scene) : find_demo_scene());
  if (o.frames) p.request.frames = *o.frames;
  if (o.spp) p.request.spp = *o.spp;
  if (o.samples_per_task) p.request.samples_per_task = *o.samples_per_task;
  apply_sampling_flags(p.request.sampling, o.sampling);
  p.request.overrides.half = o.half;
  p.workers = std::max(1, o.workers.value_or(p.settings.up.workers));
  // The workers share this machine's cores: at most `tasks` renders run at
  // once, so each gets cores / min(workers, tasks) threads. (Splitting a frame
  // over workers on one machine does not make it faster: the same cores, plus
  // each task's own scene setup and a merge — bench/farm_overhead.sh.)
  int concurrent = p.workers;
  try {
    const std::vector<int> list = parse_frame_range(p.request.frames);
    const JobRequest r = settle_job_request(p.request, list.front());
    const int frames = int(list.size());
    const int spp = r.sampling.frame_spp(r.spp);
    const int per_frame =
        r.samples_per_task > 0 ? (spp + r.samples_per_task - 1) / r.samples_per_task : 1;
    concurrent = std::clamp(frames * per_frame, 1, p.workers);
  } catch (const JobRequestError&) {
    throw;  // a usage error, before anything starts
  } catch (const std::exception&) {
    // Bad frames or scene: submit_job reports it properly later.
  }
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  p.threads_per_render = std::max(1, cores / concurrent);
  p.data_dir = expand_user(o.data_dir.value_or(p.settings.up.data_dir));
  p.out_dir = expand_user(o.output_dir.value_or(p.settings.up.output_dir));
  return p;
}

// The workers: threads here, each rendering in child processes. Their info
// chatter is hidden while they run (it would break the progress bar); their
// warnings still show.
class LocalWorkers {
 public:
  LocalWorkers(const UpPlan& plan, const Server& server) : level_(spdlog::get_level()) {
    export_parent_pid();  // renders and merges die with `vesper up` (parent_watch.h)
    for (int i = 0; i < plan.workers; ++i) {
      WorkerConfig wc = worker_config(plan.settings);
      wc.server_url = server.url();
      wc.token = server.worker_token();
      wc.name = fmt::format("up-{}", i + 1);
      wc.cache_dir = plan.data_dir / "worker-cache";
      wc.idle_backoff_min = 0.05;  // one machine: poll eagerly
      wc.idle_backoff_max = 0.5;
      wc.render_threads = plan.threads_per_render;
      workers_.push_back(std::make_unique<Worker>(wc));
    }
    for (auto& w : workers_) g_workers.push_back(w.get());
    on_stop_signals(on_up_signal);
    hide_info();
    for (auto& w : workers_) threads_.emplace_back([&w] { w->run(); });
  }
  ~LocalWorkers() { stop(); }

  void hide_info() const { spdlog::set_level(std::max(level_, spdlog::level::warn)); }
  void show_info() const { spdlog::set_level(level_); }
  void stop() {
    if (workers_.empty()) return;
    for (auto& w : workers_) w->request_stop();
    for (auto& t : threads_) t.join();
    threads_.clear();
    g_workers.clear();
    // Their keep-alive connections close with them; otherwise the server's stop
    // waits out the keep-alive timeout.
    workers_.clear();
    show_info();
  }

 private:
  spdlog::level::level_enum level_;
  std::vector<std::unique_ptr<Worker>> workers_;
  std::vector<std::thread> threads_;
};

// An interrupted earlier `vesper up` may have left unfinished jobs in the data
// dir: they would take the workers first. Its finished work stays (and is
// reused where the inputs are the same).
void cancel_leftover_jobs(FarmClient& client, const std::filesystem::path& data_dir) {
  const auto previous =
      client.get_json(std::string(protocol::paths::kJobs)).get<protocol::JobList>();
  for (const protocol::JobSummary& j : previous.jobs)
    if (!j.ended()) {
      client.post_json(protocol::job_action_path(j.id, protocol::JobAction::Cancel),
                       nlohmann::json::object());
      spdlog::warn("canceled job {} '{}' left unfinished by an earlier `vesper up` in {}", j.id,
                   escape_control_characters(j.name), data_dir.string());
    }
}

// Ctrl-C: the frames already done are fetched (and printed, one path a
// line) before `up` exits 130 saying which are missing. A second Ctrl-C
// stops at once (exit_on_second_signal).
int fetch_after_interrupt(const UpPlan& plan, FarmClient& client, int64_t job) {
  const FetchedFrames f = fetch_frames(client, job, plan.out_dir);
  for (const auto& p : f.written) std::printf("%s\n", p.string().c_str());
  std::fflush(stdout);
  const std::string missing = format_frame_list(f.missing);
  spdlog::warn("interrupted: {}; fetched {} finished frame(s) into {}; missing frames: {}",
               describe_job(client.get_job(job)), f.written.size(), plan.out_dir.string(),
               missing.empty() ? "none" : missing);
  spdlog::warn(
      "the job is kept in {} (`vesper server --data-dir {}` serves it, `vesper fetch` "
      "gets its frames)",
      plan.data_dir.string(), plan.data_dir.string());
  return 130;
}

// Submits, waits (progress bar), stops the workers, fetches. Returns the exit
// code: 0, 3 (frames missing), 130 (interrupted); throws on other failures.
int submit_wait_fetch(const UpPlan& plan, Server& server, LocalWorkers& workers,
                      FetchedFrames& fetched) {
  FarmClient client(server.url(), server.submitter_token());
  cancel_leftover_jobs(client, plan.data_dir);
  const Submitted s = submit_job(client, plan.request);
  workers.show_info();
  spdlog::info("submitted job {} '{}': frames {}, {} tasks", s.id, plan.request.name,
               plan.request.frames, s.task_count);
  workers.hide_info();
  wait_for_job(client, s.id, true, [] { return g_stop.load(); });
  workers.stop();
  if (g_stop) return fetch_after_interrupt(plan, client, s.id);
  fetched = fetch_frames(client, s.id, plan.out_dir);  // waits for the merges
  // After the merges: the job with the noise its frames reached.
  const auto finished = client.get_job(s.id);
  spdlog::info("{}", describe_job(finished));
  return fetched.missing.empty() ? 0 : 3;
}

// The scene's recipe (comp.json beside it, or --comp) over the fetched
// frames; returns the files written. Throws on a failing composite.
std::vector<std::filesystem::path> composite(const UpCommandOptions& o, const UpPlan& plan,
                                             const FetchedFrames& fetched) {
  std::vector<std::filesystem::path> written;
  const std::filesystem::path recipe =
      o.comp ? std::filesystem::path(*o.comp) : plan.request.scene.parent_path() / "comp.json";
  if (o.no_comp || fetched.written.empty() || !std::filesystem::exists(recipe)) return written;
  const CompRecipe r = recipe_for_frames(recipe, fetched, plan.out_dir);
  const CompReport report = run_comp(r);
  for (const auto& f : report.frames)
    for (const auto& p : {f.image, f.exr, f.histogram, f.histogram_plot})
      if (!p.empty()) written.push_back(p);
  return written;
}

// Results on stdout (one path a line); where it all is on stderr (not with -q).
void print_summary(const UpPlan& plan, const FetchedFrames& fetched,
                   const std::vector<std::filesystem::path>& comp_outputs, double seconds) {
  for (const auto& p : fetched.written) std::printf("%s\n", p.string().c_str());
  for (const auto& p : comp_outputs) std::printf("%s\n", p.string().c_str());
  if (!spdlog::should_log(spdlog::level::info)) return;
  const int n = plan.workers;
  std::fprintf(stderr, "\nvesper up: %d worker%s, %.1f s\n", n, n == 1 ? "" : "s", seconds);
  std::fprintf(stderr, "  frames:     %zu in %s\n", fetched.written.size(),
               std::filesystem::path(fetched.pattern).parent_path().string().c_str());
  if (!comp_outputs.empty())
    std::fprintf(stderr, "  composite:  %zu files (image, EXR, histogram JSON + plot)\n",
                 comp_outputs.size());
  std::fprintf(stderr, "  farm data:  %s (jobs.sqlite, blobs/, tokens.json)\n",
               plan.data_dir.string().c_str());
}

}  // namespace

int run_up(const UpCommandOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  UpPlan plan;
  try {
    plan = plan_up(o);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  // 1. The server, on a free loopback port so `up` never collides with a farm.
  ServerConfig sc = server_config(plan.settings);
  sc.data_dir = plan.data_dir;
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
  spdlog::info("farm: {} worker{} on this machine", plan.workers, plan.workers == 1 ? "" : "s");

  // 2. Workers, 3. submit, wait, fetch.
  int rc = 0;
  FetchedFrames fetched;
  try {
    LocalWorkers workers(plan, *server);
    rc = submit_wait_fetch(plan, *server, workers, fetched);
    if (rc == 130) return rc;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return dynamic_cast<const SceneError*>(&e) ? 2 : 1;
  }
  server->stop();

  // 4. Composite with the scene's recipe, if any.
  std::vector<std::filesystem::path> comp_outputs;
  try {
    comp_outputs = composite(o, plan, fetched);
  } catch (const std::exception& e) {
    spdlog::error("composite: {}", e.what());
    rc = 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  print_summary(plan, fetched, comp_outputs, seconds);
  return rc;
}

}  // namespace vesper::cli
