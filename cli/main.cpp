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
  r->add_option("--aov", render.aovs, "Extra AOVs: comma-separated from albedo,normal,depth");
  r->add_option("--sample-begin", render.sample_begin,
                "First sample index of this range (for split renders)")
      ->check(CLI::NonNegativeNumber);
  r->add_option("--sample-end", render.sample_end, "One past the last sample index (default: spp)")
      ->check(CLI::NonNegativeNumber);
  r->add_flag("-q,--quiet", render.quiet, "Print only the output path");

  CLI11_PARSE(app, argc, argv);
  try {
    if (r->parsed()) return vesper::cli::run_render(render);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
