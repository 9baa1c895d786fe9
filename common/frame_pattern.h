#pragma once
// Frame patterns: a run of '#' in a file name stands for the frame number,
// zero-padded to the run's length (`smoke.####.vdb`, frame 7 -> `smoke.0007.vdb`;
// a number longer than the run is written whole). Only the first run of the
// file name counts, and only in the file name (not in a folder). One
// definition for the scene's per-frame files, `vesper render -o`, the
// compositor's sequences and the farm's packing of sequences.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>

namespace vesper {

// Position and length of the first run of '#' in `name` ({0, 0}: none).
std::pair<size_t, size_t> find_frame_pattern(const std::string& name);

// Whether the file name of `path` holds a frame pattern.
bool has_frame_pattern(const std::filesystem::path& path);

// `pattern` with the pattern of its file name replaced by `frame`, zero-padded.
std::filesystem::path frame_path(const std::filesystem::path& pattern, long frame);

}  // namespace vesper
