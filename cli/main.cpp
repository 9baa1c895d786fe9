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

  CLI11_PARSE(app, argc, argv);
  try {
    if (r->parsed()) return vesper::cli::run_render(render);
    if (me->parsed()) return vesper::cli::run_merge(merge);
    if (co->parsed()) return vesper::cli::run_comp(comp);
    if (vc->parsed()) return vesper::cli::run_vdb_cloud(vdb_cloud);
    if (vi->parsed()) return vesper::cli::run_vdb_info(vdb_info);
    if (hi->parsed()) return vesper::cli::run_hist(hist);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
