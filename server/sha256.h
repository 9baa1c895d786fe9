#pragma once
// SHA-256 (OpenSSL EVP) and the one accepted spelling of a hash: 64 lower-case
// hex digits. Anything else (upper case, '..', '/', other lengths) is refused
// before it gets near a file name.
#include <string>
#include <string_view>

namespace vesper {

std::string sha256_hex(std::string_view data);
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

// n random bytes from OpenSSL's CSPRNG, hex encoded (2n characters).
std::string random_hex(int bytes);

// Compares in time that depends only on the lengths, not on where the
// strings differ.
bool constant_time_equal(std::string_view a, std::string_view b);

}  // namespace vesper
