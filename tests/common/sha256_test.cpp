// SHA-256 against the FIPS 180-2 test vectors; streaming, files, the accepted
// spelling of a hash, random tokens.
#include "common/sha256.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>

#include "common/secret_token.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

constexpr const char* kAbc = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
constexpr const char* kEmpty = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";
constexpr const char* kTwoBlocks =
    "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1";
constexpr const char* kMillionA =
    "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0";

TEST(Sha256, KnownVectors) {
  EXPECT_EQ(sha256_hex("abc"), kAbc);
  EXPECT_EQ(sha256_hex(""), kEmpty);
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"), kTwoBlocks);
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')), kMillionA);
}

TEST(Sha256, StreamingEqualsOneShot) {
  Sha256 h;
  h.update("ab");
  h.update("");
  h.update("c");
  EXPECT_EQ(h.hex(), kAbc);
}

TEST(Sha256, FilesAreHashedInChunks) {
  const test::TempDir dir("common");
  const std::string million(1000000, 'a');  // several 64 KiB reads
  std::ofstream(dir / "a", std::ios::binary) << million;
  std::ofstream(dir / "empty", std::ios::binary);
  EXPECT_EQ(sha256_file(dir / "a"), kMillionA);
  EXPECT_EQ(sha256_file(dir / "empty"), kEmpty);
  EXPECT_EQ(sha256_file(dir / "missing"), std::nullopt);
}

TEST(Sha256, OnlyLowerCaseHexOf64DigitsIsAHash) {
  EXPECT_TRUE(is_sha256_hex(kAbc));
  std::string upper = kAbc;
  upper[0] = 'B';
  EXPECT_FALSE(is_sha256_hex(upper));
  EXPECT_FALSE(is_sha256_hex(std::string(kAbc) + "0"));
  EXPECT_FALSE(is_sha256_hex(std::string(kAbc).substr(0, 63)));
  EXPECT_FALSE(is_sha256_hex("../" + std::string(kAbc).substr(3)));
  EXPECT_FALSE(is_sha256_hex(""));
}

TEST(SecretToken, RandomHexHasTheLengthAndDiffers) {
  std::set<std::string> seen;
  for (int i = 0; i < 100; ++i) {
    const std::string t = random_hex(32);
    EXPECT_TRUE(is_sha256_hex(t)) << t;  // 32 bytes = 64 lower-case hex digits
    seen.insert(t);
  }
  EXPECT_EQ(seen.size(), 100u);
  EXPECT_EQ(random_hex(8).size(), 16u);
}

TEST(SecretToken, ConstantTimeEqual) {
  EXPECT_TRUE(constant_time_equal("secret", "secret"));
  EXPECT_TRUE(constant_time_equal("", ""));
  EXPECT_FALSE(constant_time_equal("secret", "secreT"));
  EXPECT_FALSE(constant_time_equal("secret", "secret2"));
  EXPECT_FALSE(constant_time_equal("secret", ""));
}

}  // namespace
}  // namespace vesper
