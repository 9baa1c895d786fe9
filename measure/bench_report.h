#pragma once
// The files of a run in `vesper bench -o DIR`: bench.json
// (`vesper-bench-report/1`, docs/bench.md), bench.csv (one row per
// measurement), table.md, and the plot PNGs (bench_plot.h). Every file
// appears atomically.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "measure/bench_result.h"

namespace vesper::measure {

inline constexpr const char* kBenchReportFormat = "vesper-bench-report/1";

nlohmann::json bench_json(const BenchReport& report);
// Header: scene,kind,renderer,spp,render_seconds,wall_seconds,relmse,
// reference_noise_floor,reference_cached
std::string bench_csv(const BenchReport& report);

// Writes everything into `dir` (created); returns the files written. Throws
// FileWriteError, ImageIoError or filesystem_error naming the file.
std::vector<std::filesystem::path> write_bench_outputs(const BenchReport& report,
                                                       const std::filesystem::path& dir);

}  // namespace vesper::measure
