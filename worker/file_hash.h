#pragma once
// SHA-256 (OpenSSL EVP) of a file, hex encoded; and the accepted spelling of
// a blob name (64 lower-case hex digits), checked before it becomes a path.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace vesper::worker_detail {

// nullopt if the file cannot be read.
std::optional<std::string> sha256_file(const std::filesystem::path& file);
std::string sha256_hex(std::string_view data);
bool is_blob_name(std::string_view s);

}  // namespace vesper::worker_detail
