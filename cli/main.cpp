// The `vesper` executable. CLI11 is a heavy header: it lives in this file only;
// each subcommand's work is in its own <name>_command.cpp. Here: one
// registration function per subcommand group, the numeric checks, usage
// errors (exit 2, with "did you mean") and the dispatch to the parsed command.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <functional>
#include <memory>

#include "cli/commands.h"
#include "cli/nearest_name.h"
#include "cli/number_checks.h"
#include "cli/progress.h"

namespace vesper::cli {
namespace {

constexpr int kUsageError = 2;  // cli/README.md: 2 = bad input (flags, scene, config)

// Which subcommand was parsed and what it runs: CLI11 parses, the run
// functions (returning the exit code) are called after it, outside its callbacks.
class Dispatch {
 public:
  void on(const CLI::App* sub, std::function<int()> run) {
    runs_.emplace_back(sub, std::move(run));
  }
  int run() const {
    for (const auto& [sub, run] : runs_)
      if (sub->parsed()) return run();
    return 0;
  }

 private:
  std::vector<std::pair<const CLI::App*, std::function<int()>>> runs_;
};

// Numeric flags whose messages name their bound (cli/number_checks.h says why).
CLI::Validator at_least(long long min) {
  return {[min](std::string& s) { return check_at_least(s, min); }, ">= " + std::to_string(min)};
}

CLI::Validator greater_than_zero() {
  return {[](std::string& s) { return check_greater_than_zero(s); }, "> 0"};
}

// -q on every command: warnings and errors only, no progress; stdout, which
// carries results, is unchanged.
void add_quiet(CLI::App* sub, bool* field = nullptr) {
  sub->add_flag_callback(
      "-q,--quiet",
      [field] {
        if (field) *field = true;
        spdlog::set_level(spdlog::level::warn);
        silence_progress();
      },
      "Quiet: print results only (no progress or info logs)");
}

void add_sampling_flags(CLI::App* c, SamplingFlags& f) {
  c->add_option("--noise-target", f.noise_target,
                "Adaptive sampling: a pixel stops once its estimated relative error of the mean "
                "is below this (e.g. 0.02); overrides render.noise_target")
      ->check(greater_than_zero());
  c->add_option("--min-spp", f.min_spp, "Adaptive sampling: samples every pixel takes first")
      ->check(at_least(1));
  c->add_option("--max-spp", f.max_spp,
                "Adaptive sampling: most samples per pixel (default: the spp)")
      ->check(at_least(1));
  c->add_option("--time-limit", f.time_limit,
                "Stop sampling at the end of the pass in which this many seconds have passed")
      ->check(greater_than_zero());
}

void add_render(CLI::App& app, Dispatch& dispatch) {
  auto o = std::make_shared<RenderCommandOptions>();
  auto* r = app.add_subcommand("render", "Render a vesper-scene/1 file to a multi-layer OpenEXR");
  r->add_option("scene", o->scene, "Scene file (JSON)")->required()->check(CLI::ExistingFile);
  r->add_option("-o,--output", o->output,
                "Output: .exr (every layer), .png/.jpg/.tif (the beauty through the default "
                "display transform, as `vesper comp`), or .vpartial with --partial; #### in the "
                "name = the frame number (--frame, --frames), zero-padded")
      ->required();
  r->add_option("--spp", o->spp, "Samples per pixel (overrides render.spp)")->check(at_least(1));
  r->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(at_least(1));
  r->add_option("--seed", o->seed, "Random seed (overrides render.seed)")->check(at_least(0));
  r->add_option(
      "--aov", o->aovs,
      "Extra AOVs, comma-separated: albedo, normal, depth, emission, diffuse_direct, "
      "diffuse_indirect, specular_direct, specular_indirect, volume_direct, volume_indirect, "
      "variance (of the pixel mean), spp (samples taken), cryptomatte (id mattes by object "
      "and material)");
  add_sampling_flags(r, o->sampling);
  r->add_option("--scale", o->scale,
                "Render the film at this fraction of its size (e.g. 0.25 for previews and "
                "regression suites); the camera is unchanged")
      ->check(greater_than_zero());
  r->add_option("--clamp", o->clamp,
                "Indirect sample clamp (biased, off by default): scale each sample's indirect "
                "light down to at most this in its largest RGB component; overrides render.clamp")
      ->check(greater_than_zero());
  r->add_flag("--photon-merging", o->photon_merging,
              "Photon merging in fog (biased, off); overrides render.photon_merging");
  r->add_option("--photon-radius", o->photon_radius, "Its radius; overrides render.photon_radius")
      ->check(greater_than_zero());
  r->add_flag("--half", o->half,
              "Write colour channels as half floats (data channels such as depth, normal, "
              "variance and spp stay float32); overrides film.pixel_type");
  r->add_flag("--layer-variance", o->layer_variance,
              "Also write <layer>.variance.R/G/B for every RGB AOV and layer (costs 192 bytes "
              "per pixel and layer while rendering)");
  r->add_option("--sample-begin", o->sample_begin,
                "First sample index of this range (for split renders)")
      ->check(at_least(0));
  r->add_option("--sample-end", o->sample_end, "One past the last sample index (default: spp)")
      ->check(at_least(0));
  auto* frame = r->add_option("--frame", o->frame,
                              "Frame number (may be negative): the scene's state at that frame "
                              "(keys, #### files), a seed of its own; fills #### in -o");
  r->add_option("--frames", o->frames,
                "Render frames 1-24, 1-24x2, 1,5,9 in turn, each as with --frame; -o needs ####")
      ->excludes(frame);
  r->add_flag("--partial", o->partial,
              "Write a partial render (exact sample sums) for `vesper merge` instead of an EXR");
  r->add_flag("--scene-dir-only", o->scene_dir_only,
              "Refuse files the scene references outside its directory (absolute paths, '..'): "
              "what a farm worker renders, since the scene is not its own");
  add_quiet(r, &o->quiet);
  dispatch.on(r, [o] { return run_render(*o); });

  auto m = std::make_shared<MergeCommandOptions>();
  auto* me = app.add_subcommand(
      "merge", "Merge partial renders of disjoint sample ranges of one frame into one EXR");
  me->add_option("inputs", m->inputs, "Partial render files (vesper render --partial)")
      ->required()
      ->check(CLI::ExistingFile);
  me->add_option("-o,--output", m->output,
                 "Output .exr (or .png/.jpg/.tif: the beauty); #### = the partials' frame")
      ->required();
  add_quiet(me, &m->quiet);
  dispatch.on(me, [m] { return run_merge(*m); });
}

void add_comp(CLI::App& app, Dispatch& dispatch) {
  auto o = std::make_shared<CompCommandOptions>();
  auto* co = app.add_subcommand(
      "comp", "Composite layered EXR passes: a recipe (JSON) or an EXR with quick flags");
  co->add_option("input", o->input, "Recipe (.json), or an EXR / frame.####.exr sequence")
      ->required();
  co->add_option("--layer", o->layers, "Add a layer: NAME[:GAIN[:add|over]] (repeatable)");
  co->add_flag("--no-beauty", o->no_beauty, "Do not start from the beauty");
  co->add_option("--exposure", o->exposure, "Grade exposure (stops)");
  co->add_option("--cdl-slope", o->cdl_slope, "ASC CDL slope r,g,b");
  co->add_option("--cdl-offset", o->cdl_offset, "ASC CDL offset r,g,b");
  co->add_option("--cdl-power", o->cdl_power, "ASC CDL power r,g,b");
  co->add_option("--saturation", o->saturation, "ASC CDL saturation");
  co->add_option("--look", o->look, "LUT look file (.cube, ...)");
  co->add_option("--config", o->config, "OCIO config (default: $OCIO, else bundled)");
  co->add_option("--display", o->display, "OCIO display (default sRGB)");
  co->add_option("--view", o->view, "OCIO view (default Standard)");
  co->add_option("-o,--output", o->output, "Display image (.png, .jpg, .tif)");
  co->add_option("--bit-depth", o->bit_depth, "Image bit depth: 8 (default) or 16");
  co->add_option("--exr", o->exr, "Graded scene-linear EXR");
  co->add_option("--hist", o->hist, "Histogram JSON (default: <image>.hist.json)");
  co->add_option("--hist-plot", o->hist_plot, "Histogram PNG plot");
  add_quiet(co, &o->quiet);
  dispatch.on(co, [o] { return run_comp(*o); });
}

void add_vdb(CLI::App& app, Dispatch& dispatch) {
  auto* vdb =
      app.add_subcommand("vdb", "OpenVDB volumes: generate a procedural cloud, inspect a file");
  vdb->require_subcommand(1);
  auto c = std::make_shared<VdbCloudOptions>();
  auto* vc =
      vdb->add_subcommand("cloud", "Write a procedural cumulus cloud as an OpenVDB fog volume");
  vc->add_option("-o,--output", c->output, "Output .vdb path")->required();
  vc->add_option("--resolution", c->resolution, "Voxels across (height is half)")
      ->check(CLI::Range(8, 1024));
  vc->add_option("--seed", c->seed, "Random seed of the sphere cluster and the noise")
      ->check(at_least(0));
  vc->add_option("--voxel-size", c->voxel_size, "World units per voxel (default 2.56/resolution)")
      ->check(greater_than_zero());
  vc->add_option("--noise-amplitude", c->noise_amplitude,
                 "fBm displacement (cloud half-widths, 0..0.3)");
  vc->add_option("--noise-octaves", c->noise_octaves, "fBm octaves (0..12)");
  vc->add_option("--grid", c->grid, "Grid name (default density)");
  vc->add_option("--frames", c->frames,
                 "An evolving cloud, one file a frame (1-24, 1-24x2): -o needs #### (frame 1 is "
                 "the still cloud)");
  add_quiet(vc, &c->quiet);
  dispatch.on(vc, [c] { return run_vdb_cloud(*c); });

  auto i = std::make_shared<VdbInfoOptions>();
  auto* vi = vdb->add_subcommand(
      "info", "List the grids of a .vdb file: type, active voxels, bbox, value range");
  vi->add_option("file", i->file, ".vdb file")->required();
  add_quiet(vi);
  dispatch.on(vi, [i] { return run_vdb_info(*i); });
}

void add_hist(CLI::App& app, Dispatch& dispatch) {
  auto h = std::make_shared<HistCommandOptions>();
  auto* hi = app.add_subcommand("hist",
                                "Luminosity histogram of an image; with --ref, the distance to a "
                                "reference and the matching exposure");
  hi->add_option("image", h->image, "Image (PNG/JPEG/TIFF display-referred; EXR scene-linear)")
      ->required();
  hi->add_option("--ref", h->reference, "Reference image to compare with");
  hi->add_option("--weights", h->weights,
                 "Luminance weights: rec709 (default) or luminosity (0.30/0.59/0.11)");
  hi->add_option("--json", h->json, "Write the histogram as JSON");
  hi->add_option("--plot", h->plot, "Write a PNG plot of the histogram");
  hi->add_flag("--log2", h->log2,
               "Primary histogram in log2 luminance (stops) instead of display values");
  hi->add_option("--config", h->ocio_config,
                 "OCIO config for EXR inputs (default: $OCIO, else bundled)");
  hi->add_option("--display", h->display, "OCIO display for EXR inputs (default sRGB)");
  hi->add_option("--view", h->view, "OCIO view for EXR inputs (default Standard)");
  add_quiet(hi);
  dispatch.on(hi, [h] { return run_hist(*h); });
}

// --config for every farm command; --server and --token for its clients.
void add_farm_options(CLI::App* sub, FarmOptions& f, bool remote) {
  sub->add_option("--config", f.config,
                  "Farm settings (TOML; see configs/farm.toml for every key and default)")
      ->check(CLI::ExistingFile);
  add_quiet(sub);
  if (!remote) return;
  sub->add_option("--server", f.server, "Server URL (default $VESPER_SERVER, else the config's)");
  sub->add_option("--token", f.token,
                  "Bearer token (default $VESPER_TOKEN / $VESPER_WORKER_TOKEN, else the "
                  "tokens.json of the server on this machine)");
}

void add_server_and_worker(CLI::App& app, Dispatch& dispatch) {
  auto s = std::make_shared<ServerCommandOptions>();
  auto* sv = app.add_subcommand("server", "Run the farm server (HTTP API) until SIGINT/SIGTERM");
  add_farm_options(sv, s->farm, false);
  sv->add_option("--data-dir", s->data_dir, "Data dir (tokens.json, jobs.sqlite, blobs/)");
  sv->add_option("--host", s->host, "Address to bind (default 127.0.0.1)");
  sv->add_option("--port", s->port, "Port (default 8765; 0 = any free port)")
      ->check(CLI::Range(0, 65535));
  sv->add_option("--trust-renderer", s->trusted_renderers,
                 "Reuse results of this renderer build (sha256sum of its vesper binary); "
                 "repeatable, besides the config's trusted_renderers and the server's own build");
  dispatch.on(sv, [s] { return run_server(*s); });

  auto t = std::make_shared<TokensCommandOptions>();
  auto* tk = app.add_subcommand("tokens", "List, add, revoke the farm's worker tokens");
  add_farm_options(tk, t->farm, false);
  tk->add_option("--data-dir", t->data_dir, "Data dir of the server (holds tokens.json)");
  tk->require_subcommand(1);
  for (const char* action : {"list", "add-worker", "revoke", "disable-shared", "enable-shared"}) {
    const std::string a = action;
    auto* sub =
        tk->add_subcommand(a, a == "list" ? "Worker tokens and whether each is enabled (no secrets)"
                              : a == "add-worker"     ? "Make a token for one worker; prints it"
                              : a == "revoke"         ? "Refuse a worker's token from now on"
                              : a == "disable-shared" ? "Refuse the shared worker token"
                                                      : "Accept the shared worker token again");
    if (a == "add-worker" || a == "revoke")
      sub->add_option("name", t->name, "Worker name")->required();
    add_quiet(sub);
    dispatch.on(sub, [t, a] {
      t->action = a;
      return run_tokens(*t);
    });
  }

  auto w = std::make_shared<WorkerCommandOptions>();
  auto* wk = app.add_subcommand("worker", "Pull tasks from a farm server and render them");
  add_farm_options(wk, w->farm, true);
  wk->add_option("--name", w->name, "Name shown by the server (default: hostname)");
  wk->add_option("--cache-dir", w->cache_dir, "Blob cache and render temp files");
  wk->add_option("--renderer", w->renderer,
                 "Executable run as `RENDERER render ...` per task (default: this vesper)")
      ->check(CLI::ExistingFile);
  wk->add_option("--threads", w->threads, "Render threads per task (default: all cores)")
      ->check(at_least(1));
  wk->add_option("--max-tasks", w->max_tasks, "Exit after this many tasks");
  wk->add_flag("--exit-when-idle", w->exit_when_idle, "Exit when the server has no work");
  dispatch.on(wk, [w] { return run_worker(*w); });
}

void add_submit(CLI::App& app, Dispatch& dispatch) {
  auto o = std::make_shared<SubmitCommandOptions>();
  auto* sb = app.add_subcommand(
      "submit", "Submit a scene (with its meshes, images, volumes) or a vesper-job/1 file");
  add_farm_options(sb, o->farm, true);
  sb->add_option("input", o->input, "Scene file or job file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  sb->add_option("--frames", o->frames, "Frames: 1-100, 1-100x5, 1,5,9 (default 1)");
  sb->add_option("--name", o->name, "Job name (default: the scene's folder)");
  sb->add_option("--spp", o->spp, "Samples per pixel (default: the scene's)")
      ->check(CLI::Range(1, 1 << 20));
  sb->add_option("--split", o->samples_per_task,
                 "Samples per task: split each frame over several workers, merged exactly")
      ->check(at_least(0));
  sb->add_option("--priority", o->priority, "Higher runs first (default 50)");
  sb->add_option("--max-attempts", o->max_attempts, "Attempts per task (default 3)")
      ->check(CLI::Range(1, 100));
  add_sampling_flags(sb, o->sampling);  // per frame; a split frame's tasks share it
  sb->add_flag("--half", o->half,
               "Half-float colour channels in every frame (as `vesper render --half`; a job "
               "file's \"half\": true)");
  sb->add_flag("--wait", o->wait, "Wait for the job with a progress bar");
  sb->add_flag("--dry-run", o->dry_run, "Validate only; create nothing");
  dispatch.on(sb, [o] { return run_submit(*o); });
}

void add_job_commands(CLI::App& app, Dispatch& dispatch) {
  auto o = std::make_shared<JobCommandOptions>();
  auto add_job = [&](const char* name, const char* help, bool required,
                     int (*run)(const JobCommandOptions&)) {
    auto* sub = app.add_subcommand(name, help);
    add_farm_options(sub, o->farm, true);
    if (required) sub->add_option("job", o->job, "Job id")->required();
    dispatch.on(sub, [o, run] { return run(*o); });
    return sub;
  };
  auto* st = add_job("status", "Jobs on the farm, or one job's tasks", false, run_status);
  st->add_option("job", o->job, "Job id");
  st->add_flag("--json", o->json, "Print the server's JSON");
  add_job("cancel", "Cancel a job (running tasks stop at their next heartbeat)", true, run_cancel);
  add_job("pause", "Pause a job (no new tasks are leased; running ones finish)", true, run_pause);
  add_job("resume", "Resume a paused job", true, run_resume);
  auto* wl =
      add_job("workers", "Workers registered with the farm, and what they run", false, run_workers);
  wl->add_flag("--json", o->json, "Print the server's JSON");
  wl->add_flag("--prune", o->prune, "Remove offline and lost workers (says how many)");
  auto* de = add_job("delete", "Delete a finished job; frees the blobs no other job uses", true,
                     run_delete);
  de->add_flag("--cancel", o->cancel_first, "Cancel the job first if it is still active");
  add_job("retry", "Requeue a job's failed tasks (and clear its blocklist)", true, run_retry);
  auto* lg = add_job("logs", "Log tails of a job's tasks (each task keeps its last render's)", true,
                     run_logs);
  lg->add_option("--task", o->task, "Only this task's log (a task id from `vesper status JOB`)");
  auto* fe =
      add_job("fetch", "Download a job's finished frames (merged per frame)", true, run_fetch);
  fe->add_option("-o,--output", o->output_dir, "Directory for <job>.####.exr")->required();
}

void add_up(CLI::App& app, Dispatch& dispatch) {
  auto o = std::make_shared<UpCommandOptions>();
  auto* u = app.add_subcommand(
      "up", "A local farm: server + N workers; submit the demo scene, wait, fetch, composite");
  u->add_option("--config", o->config, "Farm settings (TOML; configs/farm.toml)")
      ->check(CLI::ExistingFile);
  u->add_option("--workers", o->workers, "Worker count (default 2)")->check(CLI::Range(1, 256));
  u->add_option("--scene", o->scene, "Scene (default scenes/night-room/scene.json)")
      ->check(CLI::ExistingFile);
  u->add_option("--frames", o->frames, "Frames (default 1)");
  u->add_option("--spp", o->spp, "Samples per pixel (default: the scene's)")
      ->check(CLI::Range(1, 1 << 20));
  u->add_option("--split", o->samples_per_task, "Samples per task (0 = whole frames)")
      ->check(at_least(0));
  add_sampling_flags(u, o->sampling);
  u->add_flag("--half", o->half, "Half-float colour channels in every frame (render --half)");
  u->add_option("--comp", o->comp, "Composite recipe (default: comp.json beside the scene)");
  u->add_flag("--no-comp", o->no_comp, "Do not composite");
  u->add_option("--data-dir", o->data_dir, "Farm data dir (default out/farm)");
  u->add_option("-o,--output", o->output_dir, "Frames and composites (default out/farm-frames)");
  add_quiet(u);
  dispatch.on(u, [o] { return run_up(*o); });
}

void add_regress(CLI::App& app, Dispatch& dispatch) {
  auto o = std::make_shared<RegressCommandOptions>();
  auto* r = app.add_subcommand(
      "regress", "Re-render a regression suite and compare it with its goldens, noise-aware");
  r->add_option("suite", o->suite, "Suite file (vesper-suite/1; docs/regression.md)")
      ->required()
      ->check(CLI::ExistingFile);
  r->add_option("--goldens", o->goldens, "Folder of the golden frames")->required();
  r->add_flag("--update-goldens", o->update_goldens,
              "Render and write the goldens; compare nothing");
  auto* local = r->add_flag("--local", o->local, "Render here, in child processes (the default)");
  auto* server =
      r->add_option("--server", o->farm.server, "Render on the farm at this URL, as one batch")
          ->excludes(local);
  r->add_option("--token", o->farm.token,
                "With --server: bearer token (default $VESPER_TOKEN, else the tokens.json of the "
                "server on this machine)")
      ->needs(server);
  r->add_option("--config", o->farm.config, "With --server: farm settings (TOML)")
      ->check(CLI::ExistingFile)
      ->needs(server);
  r->add_option("--report", o->report, "Folder for report.json and index.html");
  r->add_option("--seed", o->seed, "Random seed of every render (default: the scenes')")
      ->check(at_least(0));
  r->add_option("--history", o->history, "SQLite history database, for trends");
  // Local renders only: on the farm the workers' renderer and threads are used,
  // and a task renders once.
  r->add_option("--renderer", o->renderer,
                "A `vesper render`-compatible program to run instead of this binary")
      ->check(CLI::ExistingFile)
      ->excludes(server);
  r->add_option("--repeats", o->repeats, "Renders per scene, for the timing (default 3)")
      ->check(CLI::Range(1, 100))
      ->excludes(server);
  r->add_option("--threads", o->threads, "Threads per render (default: all cores)")
      ->check(at_least(1))
      ->excludes(server);
  add_quiet(r, &o->quiet);
  dispatch.on(r, [o] { return run_regress(*o); });
}

void add_bench(CLI::App& app, Dispatch& dispatch) {
  auto o = std::make_shared<BenchCommandOptions>();
  auto* b = app.add_subcommand(
      "bench", "Measure time against error (relMSE) on the benchmark set (docs/bench.md)");
  b->add_option("-o,--output", o->output, "Folder for bench.json, bench.csv, table.md, plots")
      ->required();
  b->add_flag("--quick", o->quick, "Tiny sizes, short ladders, low-spp references: seconds");
  b->add_option("--compare", o->compare, "Also measure a peer renderer: cycles");
  b->add_option("--refs", o->refs,
                "Reference cache folder (default $XDG_CACHE_HOME/vesper/bench-refs)");
  b->add_option("--scenes", o->scenes, "The benchmark set (default bench/scenes.json)");
  b->add_option("--threads", o->threads, "Threads per render (default: all cores)")
      ->check(at_least(1));
  b->add_option("--seed", o->seed, "Seed of the measured renders (default 1)")->check(at_least(0));
  add_quiet(b, &o->quiet);
  dispatch.on(b, [o] { return run_bench(*o); });
}

// The deepest subcommand the command line reached (`vesper vdb cloud` -> cloud).
const CLI::App* innermost(const CLI::App* app) {
  while (!app->get_subcommands().empty()) app = app->get_subcommands().front();
  return app;
}

// "did you mean" for the unexpected words of a usage error: options of the
// subcommand they were given to, or its subcommands' names. CLI11 2.1 has no
// suggestions of its own, so they are computed here (nearest_name.h).
std::string suggestions(const CLI::App& app) {
  const CLI::App* at = innermost(&app);
  std::vector<std::string> options, commands;
  for (const CLI::Option* opt : at->get_options()) {
    for (const std::string& n : opt->get_lnames()) options.push_back("--" + n);
    for (const std::string& n : opt->get_snames()) options.push_back("-" + n);
  }
  for (const CLI::App* sub : at->get_subcommands([](const CLI::App*) { return true; }))
    commands.push_back(sub->get_name());
  std::string hints;
  for (std::string word : app.remaining(true)) {
    const bool is_option = word.size() > 1 && word[0] == '-';
    if (is_option) word = word.substr(0, word.find('='));
    if (const auto near = nearest_name(word, is_option ? options : commands))
      hints += word + ": did you mean " + *near + "?\n";
  }
  return hints;
}

// Usage errors exit 2 (CLI11's own codes, 105/106/109..., are not part of the
// CLI's contract); --help and --version exit 0.
int usage_error(CLI::App& app, const CLI::ParseError& e) {
  app.failure_message([](const CLI::App* a, const CLI::Error& err) {
    return std::string(err.what()) + "\n" + suggestions(*a) +
           "Run with --help for more information.\n";
  });
  return app.exit(e) == 0 ? 0 : kUsageError;
}

}  // namespace
}  // namespace vesper::cli

int main(int argc, char** argv) {
  using namespace vesper::cli;
  // Logs and progress go to stderr; stdout carries only results (paths), for scripts.
  spdlog::set_default_logger(spdlog::stderr_color_mt("vesper"));
  CLI::App app{"Vesper: an offline render farm and path tracer"};
  app.require_subcommand(1);
  app.set_version_flag("--version", VESPER_VERSION);
  Dispatch dispatch;
  add_render(app, dispatch);
  add_comp(app, dispatch);
  add_vdb(app, dispatch);
  add_hist(app, dispatch);
  add_server_and_worker(app, dispatch);
  add_submit(app, dispatch);
  add_job_commands(app, dispatch);
  add_up(app, dispatch);
  add_regress(app, dispatch);
  add_bench(app, dispatch);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e);
  }
  try {
    return dispatch.run();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
