#pragma once
// Subcommand entry points. Each lives in its own .cpp; main.cpp owns CLI11
// and only fills these option structs.
#include <optional>
#include <string>
#include <vector>

namespace vesper::cli {

// Adaptive sampling and budgets: --noise-target, --min-spp, --max-spp,
// --time-limit (render.noise_target & co. in the scene; docs/sampling.md).
struct SamplingFlags {
  std::optional<double> noise_target, time_limit;
  std::optional<int> min_spp, max_spp;
};

struct RenderCommandOptions {
  std::string scene;
  std::string output;
  std::optional<int> spp;
  std::optional<int> threads;
  std::optional<unsigned long long> seed;
  std::optional<std::string> aovs;  // comma-separated
  int sample_begin = 0;
  std::optional<int> sample_end;
  SamplingFlags sampling;
  std::optional<double> scale;  // --scale: film width and height times this
  std::optional<double> clamp;  // --clamp: overrides render.clamp (biased)
  // --photon-merging / --photon-radius: override render.photon_merging /
  // render.photon_radius (biased).
  bool photon_merging = false;
  std::optional<double> photon_radius;
  bool half = false;            // --half: half-float colour channels, whatever film.pixel_type says
  bool layer_variance = false;  // --layer-variance: <layer>.variance.R/G/B for every RGB layer
  // Frame number: decorrelates the frame's noise from other frames (the seed
  // becomes frame_seed(seed, frame)) and is stamped as vesper:frame.
  std::optional<int> frame;
  // --frames 1-24x2: render these frames in turn, each as with --frame N
  // (excludes --frame; -o needs a '#' run for more than one frame).
  std::optional<std::string> frames;
  // Write a partial render (docs/partial-format.md): the exact per-pixel
  // sample sums of [sample_begin, sample_end), which `vesper merge` combines.
  bool partial = false;
  // Refuse scene files outside the scene's directory (farm tasks).
  bool scene_dir_only = false;
  bool quiet = false;
};
int run_render(const RenderCommandOptions& options);

// vesper merge: partial renders of disjoint sample ranges of one frame ->
// one EXR, bitwise identical to a single render of the union of the ranges.
struct MergeCommandOptions {
  std::vector<std::string> inputs;  // partial files
  std::string output;               // EXR
  bool quiet = false;
};
int run_merge(const MergeCommandOptions& options);

// vesper comp: composite layered EXR passes from a recipe (docs/compositing.md)
// or from quick flags (`vesper comp in.exr --layer lightrays:0.8 -o out.png`).
struct CompCommandOptions {
  std::string input;                // recipe (.json) or an EXR / `####` sequence
  std::vector<std::string> layers;  // --layer NAME[:GAIN[:add|over]]
  bool no_beauty = false;
  std::optional<float> exposure, saturation;
  std::optional<std::string> cdl_slope, cdl_offset, cdl_power;  // r,g,b
  std::optional<std::string> look, config, display, view;
  std::optional<std::string> output, exr, hist, hist_plot;
  std::optional<int> bit_depth;
  bool quiet = false;
  bool has_quick_flags() const {
    return !layers.empty() || no_beauty || exposure || saturation || cdl_slope || cdl_offset ||
           cdl_power || look || config || display || view || output || exr || hist || hist_plot ||
           bit_depth;
  }
};
int run_comp(const CompCommandOptions& options);

// vesper vdb cloud: a procedural cloud written as an OpenVDB fog volume.
struct VdbCloudOptions {
  std::string output;
  int resolution = 128;
  unsigned long long seed = 1;
  std::optional<double> voxel_size;  // default: 2.56 / resolution (same world size)
  std::optional<float> noise_amplitude;
  std::optional<int> noise_octaves;
  std::string grid = "density";
  // --frames 1-24: an evolving cloud, frame f at CloudParams::time f - 1,
  // written to -o with its '#' run filled.
  std::optional<std::string> frames;
  bool quiet = false;
};
int run_vdb_cloud(const VdbCloudOptions& options);

// vesper vdb info: the grids of a .vdb file (type, active voxels, bbox, range).
struct VdbInfoOptions {
  std::string file;
};
int run_vdb_info(const VdbInfoOptions& options);

// vesper hist: the luminosity histogram of an image (and its distance to a reference).
struct HistCommandOptions {
  std::string image;
  std::optional<std::string> reference;  // --ref
  std::string weights = "rec709";        // rec709 | luminosity
  std::optional<std::string> json;       // --json OUT.json
  std::optional<std::string> plot;       // --plot OUT.png
  bool log2 = false;                     // primary histogram in log2 stops
  std::string ocio_config;               // for EXR inputs; empty = $OCIO or the bundled config
  std::string display = "sRGB";
  std::string view = "Standard";
};
int run_hist(const HistCommandOptions& options);

// --- The farm (server/README.md; defaults in configs/farm.toml) ---

// Where a farm command finds its settings, server and token.
struct FarmOptions {
  std::string config;                 // TOML file; empty = built-in defaults
  std::optional<std::string> server;  // URL
  std::optional<std::string> token;
};

// vesper server: serve the farm API until SIGINT/SIGTERM.
struct ServerCommandOptions {
  FarmOptions farm;
  std::optional<std::string> data_dir, host;
  std::optional<int> port;
  std::vector<std::string> trusted_renderers;  // added to the config's
};
int run_server(const ServerCommandOptions& options);

// vesper tokens list|add-worker NAME|revoke NAME|disable-shared|enable-shared:
// edits the server's tokens.json (server/tokens.h); a running server picks
// the change up at its next request.
struct TokensCommandOptions {
  FarmOptions farm;
  std::optional<std::string> data_dir;
  std::string action;  // the subcommand's name
  std::string name;    // add-worker, revoke
};
int run_tokens(const TokensCommandOptions& options);

// vesper worker: pull and render tasks until SIGINT/SIGTERM.
struct WorkerCommandOptions {
  FarmOptions farm;
  std::optional<std::string> name, cache_dir;
  // The renderer run for each task (default: this vesper binary); e.g. a
  // pinned release, or a wrapper that sets up the environment.
  std::optional<std::string> renderer;
  std::optional<int> threads;
  int max_tasks = -1;
  bool exit_when_idle = false;
};
int run_worker(const WorkerCommandOptions& options);

// vesper submit: a scene (with its assets) or a job file (vesper-job/1).
struct SubmitCommandOptions {
  FarmOptions farm;
  std::string input;
  std::optional<std::string> frames, name;
  std::optional<int> spp, samples_per_task, priority, max_attempts;
  SamplingFlags sampling;  // the job's budget per frame (docs/farm.md)
  bool half = false;       // --half: half-float colour channels (the job file's "half": true)
  bool wait = false, dry_run = false;
};
int run_submit(const SubmitCommandOptions& options);

// vesper status|cancel|pause|resume|retry|logs|fetch|workers|delete.
struct JobCommandOptions {
  FarmOptions farm;
  std::optional<long long> job;
  std::string output_dir;         // fetch
  bool json = false;              // status: the server's JSON
  bool prune = false;             // workers: remove offline and lost ones
  bool cancel_first = false;      // delete: cancel an active job first
  std::optional<long long> task;  // logs --task: one task's log
};
int run_status(const JobCommandOptions& options);
int run_cancel(const JobCommandOptions& options);
int run_pause(const JobCommandOptions& options);
int run_resume(const JobCommandOptions& options);
int run_workers(const JobCommandOptions& options);
int run_retry(const JobCommandOptions& options);
int run_logs(const JobCommandOptions& options);
int run_fetch(const JobCommandOptions& options);
int run_delete(const JobCommandOptions& options);

// vesper regress: re-render a suite, compare with goldens without alarms
// for Monte Carlo noise, report (docs/regression.md). Exit 0 nothing
// regressed, 1 something regressed or could not be compared, 2 bad input.
struct RegressCommandOptions {
  std::string suite;
  std::string goldens;
  bool update_goldens = false;
  bool local = false;
  FarmOptions farm;  // --server URL (the farm mode), --token, --config
  std::optional<std::string> report;
  std::optional<unsigned long long> seed;
  std::optional<std::string> history;
  std::optional<std::string> renderer;  // a `vesper render`-compatible program; default: this one
  int repeats = 3;                      // renders per scene, for the timing
  std::optional<int> threads;
  bool quiet = false;
};
int run_regress(const RegressCommandOptions& options);

// vesper bench: time against error of the benchmark set, per renderer, with
// cached references (docs/bench.md). Exit 0 measured, 1 a render or an
// output failed, 2 bad input (flags, scenes file, a scene).
struct BenchCommandOptions {
  std::string output;  // -o DIR
  std::string scenes = "bench/scenes.json";
  std::optional<std::string> refs;     // default: $XDG_CACHE_HOME/vesper/bench-refs
  std::optional<std::string> compare;  // a peer renderer: "cycles"
  std::optional<int> threads;
  unsigned long long seed = 1;
  bool quick = false;
  bool quiet = false;
};
int run_bench(const BenchCommandOptions& options);

// vesper up: a local server and N workers; submit, wait, fetch, composite.
struct UpCommandOptions {
  std::string config;
  std::optional<int> workers, spp, samples_per_task;
  SamplingFlags sampling;
  std::optional<std::string> scene, frames, comp, data_dir, output_dir;
  bool half = false;  // --half: the job's frames with half-float colour channels
  bool no_comp = false;
};
int run_up(const UpCommandOptions& options);

}  // namespace vesper::cli
