// vesper merge: partial renders (vesper render --partial) of disjoint sample
// ranges of one frame -> one EXR, bitwise identical to a single render of the
// union of the ranges (docs/partial-format.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/frame_output.h"
#include "cli/parent_watch.h"
#include "renderer/output/partial_io.h"

namespace vesper::cli {

namespace {

// The merged frame's number (vesper:frame, from `vesper render --frame`), for #### in -o.
std::optional<long> frame_of(const LayeredImage& image) {
  const auto it = image.metadata.find("vesper:frame");
  if (it == image.metadata.end()) return std::nullopt;
  return std::stol(it->second);
}

}  // namespace

int run_merge(const MergeCommandOptions& o) {
  if (!die_with_parent()) return 1;
  std::unique_ptr<FrameOutput> output;
  LayeredImage merged;
  std::vector<Partial> parts;
  std::filesystem::path out_path;
  try {
    output = std::make_unique<FrameOutput>(o.output, false);
    parts.reserve(o.inputs.size());
    for (const std::string& in : o.inputs) parts.push_back(read_partial(in));
    merged = merge_partials(parts);
    out_path = output->path(frame_of(merged));
  } catch (const OutputError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const PartialError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  try {
    output->write(merged, out_path);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  const int frame_spp = parts.front().frame_spp;
  const std::string& begin = merged.metadata.at("vesper:sample_begin");
  const std::string& end = merged.metadata.at("vesper:sample_end");
  if (begin != "0" || end != std::to_string(frame_spp))
    spdlog::warn("merged samples [{}, {}) of a {}-spp frame: the frame is not complete", begin, end,
                 frame_spp);
  if (!o.quiet)
    spdlog::info("merged {} partials, samples [{}, {}), into {}", parts.size(), begin, end,
                 out_path.string());
  std::printf("%s\n", out_path.string().c_str());
  return 0;
}

}  // namespace vesper::cli
