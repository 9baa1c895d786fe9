#pragma once
// The progress a child `vesper render` reports on stderr: its plain progress
// lines ("render:  40% (elapsed 1.2s, eta 1.8s)", cli/progress.cpp) when
// stderr is not a terminal.
#include <optional>
#include <string_view>

namespace vesper::worker_detail {

// The fraction (0..1) of the last progress line in `stderr_text`, or nullopt.
std::optional<double> last_render_progress(std::string_view stderr_text);

}  // namespace vesper::worker_detail
