#pragma once
// A file that appears whole or not at all: written beside its target under a
// hidden temporary name and renamed into place, so a crash or a full disk
// never leaves a half-written file where the old one was.
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace vesper {

// what() names the file and the reason; callers rethrow as their own error type.
struct FileWriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Replaces `path` with `bytes` (the folder must exist). On failure nothing
// is left behind and the old file, if any, is untouched.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace vesper
