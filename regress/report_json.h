#pragma once
// report.json (`vesper-regress-report/1`, docs/regression.md): a RunResult
// with stable keys, written for scripts, the HTML report and later reading.
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "regress/regress_result.h"

namespace vesper::regress {

constexpr const char* kReportFormat = "vesper-regress-report/1";

nlohmann::json report_to_json(const RunResult& run);

// Validates like every other Vesper document: throws JsonError naming `file`
// and the JSON path of anything missing or of the wrong type.
RunResult report_from_json(const nlohmann::json& doc, const std::string& file);

// Written atomically (a temporary file renamed over `path`); throws
// std::runtime_error naming the file.
void write_report_json(const RunResult& run, const std::filesystem::path& path);
RunResult read_report_json(const std::filesystem::path& path);

}  // namespace vesper::regress
