#pragma once
// SHA-256 (OpenSSL EVP) of bytes, streams and files, hex encoded; and the one
// accepted spelling of a hash: 64 lower-case hex digits. Anything else (upper
// case, '..', '/', other lengths) is refused before it gets near a file name.
// The farm names blobs by these hashes (server, worker, `vesper submit`).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace vesper {

std::string sha256_hex(std::string_view data);
// nullopt if the file cannot be read.
std::optional<std::string> sha256_file(const std::filesystem::path& file);
bool is_sha256_hex(std::string_view s);

// Incremental hashing for streamed uploads.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(std::string_view data);
  std::string hex();  // finishes the hash

 private:
  void* ctx_;
};

// Lower-case hex of `n` bytes (2n characters).
std::string to_hex(const unsigned char* bytes, size_t n);

}  // namespace vesper
