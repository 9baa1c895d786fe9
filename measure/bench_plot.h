#pragma once
// One scene's curves as a PNG: relMSE against render time on log-log axes
// with decade ticks, each renderer a line with markers and its reference's
// noise floor dotted, the relMSE targets as dashed horizontal lines.
#include <filesystem>
#include <vector>

#include "measure/bench_result.h"

namespace vesper::measure {

// Writes atomically; throws ImageIoError naming the file.
void write_plot_png(const SceneResult& scene, const std::vector<double>& targets,
                    const std::filesystem::path& path);

}  // namespace vesper::measure
