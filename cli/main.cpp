// The `vesper` executable. CLI11 is a heavy header: it lives in this file only;
// each subcommand's work is in its own <name>_command.cpp.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "cli/commands.h"

int main(int argc, char** argv) {
  // Logs and progress go to stderr; stdout carries only results (paths), for scripts.
  spdlog::set_default_logger(spdlog::stderr_color_mt("vesper"));
  CLI::App app{"Vesper: an offline render farm and path tracer"};
  app.require_subcommand(1);
  app.set_version_flag("--version", VESPER_VERSION);

  vesper::cli::RenderCommandOptions render;
  auto* r = app.add_subcommand("render", "Render a vesper-scene/1 file to a multi-layer OpenEXR");
  r->add_option("scene", render.scene, "Scene file (JSON)")->required()->check(CLI::ExistingFile);
  r->add_option("-o,--output", render.output, "Output EXR path")->required();
  r->add_option("--spp", render.spp, "Samples per pixel (overrides render.spp)")
      ->check(CLI::PositiveNumber);
  r->add_option("--threads", render.threads, "Worker threads (default: all cores)")
      ->check(CLI::PositiveNumber);
  r->add_option("--seed", render.seed, "Random seed (overrides render.seed)");
  r->add_option(
      "--aov", render.aovs,
      "Extra AOVs, comma-separated: albedo, normal, depth, emission, diffuse_direct, "
      "diffuse_indirect, specular_direct, specular_indirect, volume_direct, volume_indirect");
  r->add_option("--sample-begin", render.sample_begin,
                "First sample index of this range (for split renders)")
      ->check(CLI::NonNegativeNumber);
  r->add_option("--sample-end", render.sample_end, "One past the last sample index (default: spp)")
      ->check(CLI::NonNegativeNumber);
  r->add_option("--frame", render.frame,
                "Frame number: decorrelates this frame's noise from other frames' (same scene, "
                "same seed)");
  r->add_flag("--partial", render.partial,
              "Write a partial render (exact sample sums) for `vesper merge` instead of an EXR");
  r->add_flag("-q,--quiet", render.quiet, "Print only the output path");

  vesper::cli::MergeCommandOptions merge;
  auto* me = app.add_subcommand(
      "merge", "Merge partial renders of disjoint sample ranges of one frame into one EXR");
  me->add_option("inputs", merge.inputs, "Partial render files (vesper render --partial)")
      ->required()
      ->check(CLI::ExistingFile);
  me->add_option("-o,--output", merge.output, "Output EXR path")->required();
  me->add_flag("-q,--quiet", merge.quiet, "Print only the output path");

  vesper::cli::CompCommandOptions comp;
  auto* co = app.add_subcommand(
      "comp", "Composite layered EXR passes: a recipe (JSON) or an EXR with quick flags");
  co->add_option("input", comp.input, "Recipe (.json), or an EXR / frame.####.exr sequence")
      ->required();
  co->add_option("--layer", comp.layers, "Add a layer: NAME[:GAIN[:add|over]] (repeatable)");
  co->add_flag("--no-beauty", comp.no_beauty, "Do not start from the beauty");
  co->add_option("--exposure", comp.exposure, "Grade exposure (stops)");
  co->add_option("--cdl-slope", comp.cdl_slope, "ASC CDL slope r,g,b");
  co->add_option("--cdl-offset", comp.cdl_offset, "ASC CDL offset r,g,b");
  co->add_option("--cdl-power", comp.cdl_power, "ASC CDL power r,g,b");
  co->add_option("--saturation", comp.saturation, "ASC CDL saturation");
  co->add_option("--look", comp.look, "LUT look file (.cube, ...)");
  co->add_option("--config", comp.config, "OCIO config (default: $OCIO, else bundled)");
  co->add_option("--display", comp.display, "OCIO display (default sRGB)");
  co->add_option("--view", comp.view, "OCIO view (default Standard)");
  co->add_option("-o,--output", comp.output, "Display image (.png, .jpg, .tif)");
  co->add_option("--bit-depth", comp.bit_depth, "Image bit depth: 8 (default) or 16");
  co->add_option("--exr", comp.exr, "Graded scene-linear EXR");
  co->add_option("--hist", comp.hist, "Histogram JSON (default: <image>.hist.json)");
  co->add_option("--hist-plot", comp.hist_plot, "Histogram PNG plot");
  co->add_flag("-q,--quiet", comp.quiet, "Print only the output paths");

  vesper::cli::VdbCloudOptions vdb_cloud;
  vesper::cli::VdbInfoOptions vdb_info;
  auto* vdb =
      app.add_subcommand("vdb", "OpenVDB volumes: generate a procedural cloud, inspect a file");
  vdb->require_subcommand(1);
  auto* vc =
      vdb->add_subcommand("cloud", "Write a procedural cumulus cloud as an OpenVDB fog volume");
  vc->add_option("-o,--output", vdb_cloud.output, "Output .vdb path")->required();
  vc->add_option("--resolution", vdb_cloud.resolution, "Voxels across (height is half)")
      ->check(CLI::Range(8, 1024));
  vc->add_option("--seed", vdb_cloud.seed, "Random seed of the sphere cluster and the noise");
  vc->add_option("--voxel-size", vdb_cloud.voxel_size,
                 "World units per voxel (default 2.56/resolution)")
      ->check(CLI::PositiveNumber);
  vc->add_option("--noise-amplitude", vdb_cloud.noise_amplitude,
                 "fBm displacement (cloud half-widths, 0..0.3)");
  vc->add_option("--noise-octaves", vdb_cloud.noise_octaves, "fBm octaves (0..12)");
  vc->add_option("--grid", vdb_cloud.grid, "Grid name (default density)");
  vc->add_flag("-q,--quiet", vdb_cloud.quiet, "Print only the output path");
  auto* vi = vdb->add_subcommand(
      "info", "List the grids of a .vdb file: type, active voxels, bbox, value range");
  vi->add_option("file", vdb_info.file, ".vdb file")->required();

  vesper::cli::HistCommandOptions hist;
  auto* hi = app.add_subcommand("hist",
                                "Luminosity histogram of an image; with --ref, the distance to a "
                                "reference and the matching exposure");
  hi->add_option("image", hist.image, "Image (PNG/JPEG/TIFF display-referred; EXR scene-linear)")
      ->required();
  hi->add_option("--ref", hist.reference, "Reference image to compare with");
  hi->add_option("--weights", hist.weights,
                 "Luminance weights: rec709 (default) or luminosity (0.30/0.59/0.11)");
  hi->add_option("--json", hist.json, "Write the histogram as JSON");
  hi->add_option("--plot", hist.plot, "Write a PNG plot of the histogram");
  hi->add_flag("--log2", hist.log2,
               "Primary histogram in log2 luminance (stops) instead of display values");
  hi->add_option("--config", hist.ocio_config,
                 "OCIO config for EXR inputs (default: $OCIO, else bundled)");
  hi->add_option("--display", hist.display, "OCIO display for EXR inputs (default sRGB)");
  hi->add_option("--view", hist.view, "OCIO view for EXR inputs (default Standard)");

  // --- The farm ---
  auto add_farm = [](CLI::App* sub, vesper::cli::FarmOptions& f, bool remote) {
    sub->add_option("--config", f.config,
                    "Farm settings (TOML; see configs/farm.toml for every key and default)")
        ->check(CLI::ExistingFile);
    if (!remote) return;
    sub->add_option("--server", f.server, "Server URL (default $VESPER_SERVER, else the config's)");
    sub->add_option("--token", f.token,
                    "Bearer token (default $VESPER_TOKEN / $VESPER_WORKER_TOKEN, else the local "
                    "server's tokens.json)");
  };
  vesper::cli::ServerCommandOptions server;
  auto* sv = app.add_subcommand("server", "Run the farm server (HTTP API) until SIGINT/SIGTERM");
  add_farm(sv, server.farm, false);
  sv->add_option("--data-dir", server.data_dir, "Data dir (tokens.json, jobs.sqlite, blobs/)");
  sv->add_option("--host", server.host, "Address to bind (default 127.0.0.1)");
  sv->add_option("--port", server.port, "Port (default 8765; 0 = any free port)")
      ->check(CLI::Range(0, 65535));

  vesper::cli::WorkerCommandOptions worker;
  auto* wk = app.add_subcommand("worker", "Pull tasks from a farm server and render them");
  add_farm(wk, worker.farm, true);
  wk->add_option("--name", worker.name, "Name shown by the server (default: hostname)");
  wk->add_option("--cache-dir", worker.cache_dir, "Blob cache and render temp files");
  wk->add_option("--renderer", worker.renderer,
                 "Executable run as `RENDERER render ...` per task (default: this vesper)")
      ->check(CLI::ExistingFile);
  wk->add_option("--threads", worker.threads, "Render threads per task (default: all cores)")
      ->check(CLI::PositiveNumber);
  wk->add_option("--max-tasks", worker.max_tasks, "Exit after this many tasks");
  wk->add_flag("--exit-when-idle", worker.exit_when_idle, "Exit when the server has no work");

  vesper::cli::SubmitCommandOptions submit;
  auto* sb = app.add_subcommand(
      "submit", "Submit a scene (with its meshes, images, volumes) or a vesper-job/1 file");
  add_farm(sb, submit.farm, true);
  sb->add_option("input", submit.input, "Scene file or job file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  sb->add_option("--frames", submit.frames, "Frames: 1-100, 1-100x5, 1,5,9 (default 1)");
  sb->add_option("--name", submit.name, "Job name (default: the scene's folder)");
  sb->add_option("--spp", submit.spp, "Samples per pixel (default: the scene's)")
      ->check(CLI::Range(1, 1 << 20));
  sb->add_option("--split", submit.samples_per_task,
                 "Samples per task: split each frame over several workers, merged exactly")
      ->check(CLI::NonNegativeNumber);
  sb->add_option("--priority", submit.priority, "Higher runs first (default 50)");
  sb->add_option("--max-attempts", submit.max_attempts, "Attempts per task (default 3)")
      ->check(CLI::Range(1, 100));
  sb->add_flag("--wait", submit.wait, "Wait for the job with a progress bar");
  sb->add_flag("--dry-run", submit.dry_run, "Validate only; create nothing");

  vesper::cli::JobCommandOptions job;
  auto add_job = [&](const char* name, const char* help, bool required) {
    auto* sub = app.add_subcommand(name, help);
    add_farm(sub, job.farm, true);
    auto* opt = sub->add_option("job", job.job, "Job id");
    if (required) opt->required();
    return sub;
  };
  auto* st = add_job("status", "Jobs on the farm, or one job's tasks", false);
  st->add_flag("--json", job.json, "Print the server's JSON");
  auto* cn = add_job("cancel", "Cancel a job (running tasks stop at their next heartbeat)", true);
  auto* pa = add_job("pause", "Pause a job (running tasks stop at their next heartbeat)", true);
  auto* re = add_job("resume", "Resume a paused job", true);
  auto* wl = app.add_subcommand("workers", "Workers registered with the farm, and what they run");
  add_farm(wl, job.farm, true);
  wl->add_flag("--json", job.json, "Print the server's JSON");
  auto* rt = add_job("retry", "Requeue a job's failed tasks (and clear its blocklist)", true);
  auto* lg = add_job("logs", "Failure logs of a job's tasks", true);
  auto* fe = add_job("fetch", "Download a job's finished frames (merged per frame)", true);
  fe->add_option("-o,--output", job.output_dir, "Directory for <job>.####.exr")->required();

  vesper::cli::UpCommandOptions up;
  auto* u = app.add_subcommand(
      "up", "A local farm: server + N workers; submit the demo scene, wait, fetch, composite");
  u->add_option("--config", up.config, "Farm settings (TOML; configs/farm.toml)")
      ->check(CLI::ExistingFile);
  u->add_option("--workers", up.workers, "Worker count (default 2)")->check(CLI::Range(1, 256));
  u->add_option("--scene", up.scene, "Scene (default scenes/night-room/scene.json)")
      ->check(CLI::ExistingFile);
  u->add_option("--frames", up.frames, "Frames (default 1)");
  u->add_option("--spp", up.spp, "Samples per pixel (default: the scene's)")
      ->check(CLI::Range(1, 1 << 20));
  u->add_option("--split", up.samples_per_task, "Samples per task (0 = whole frames)")
      ->check(CLI::NonNegativeNumber);
  u->add_option("--comp", up.comp, "Composite recipe (default: comp.json beside the scene)");
  u->add_flag("--no-comp", up.no_comp, "Do not composite");
  u->add_option("--data-dir", up.data_dir, "Farm data dir (default out/farm)");
  u->add_option("-o,--output", up.output_dir, "Frames and composites (default out/farm-frames)");

  CLI11_PARSE(app, argc, argv);
  try {
    if (r->parsed()) return vesper::cli::run_render(render);
    if (me->parsed()) return vesper::cli::run_merge(merge);
    if (co->parsed()) return vesper::cli::run_comp(comp);
    if (vc->parsed()) return vesper::cli::run_vdb_cloud(vdb_cloud);
    if (vi->parsed()) return vesper::cli::run_vdb_info(vdb_info);
    if (hi->parsed()) return vesper::cli::run_hist(hist);
    if (sv->parsed()) return vesper::cli::run_server(server);
    if (wk->parsed()) return vesper::cli::run_worker(worker);
    if (sb->parsed()) return vesper::cli::run_submit(submit);
    if (st->parsed()) return vesper::cli::run_status(job);
    if (cn->parsed()) return vesper::cli::run_cancel(job);
    if (rt->parsed()) return vesper::cli::run_retry(job);
    if (pa->parsed()) return vesper::cli::run_pause(job);
    if (re->parsed()) return vesper::cli::run_resume(job);
    if (wl->parsed()) return vesper::cli::run_workers(job);
    if (lg->parsed()) return vesper::cli::run_logs(job);
    if (fe->parsed()) return vesper::cli::run_fetch(job);
    if (u->parsed()) return vesper::cli::run_up(up);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
