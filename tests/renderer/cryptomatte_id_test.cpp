// Cryptomatte ids: MurmurHash3_x86_32 and the uint32_to_float32 conversion,
// against the specification's own test vectors (Psyop/Cryptomatte:
// nuke/cryptomatte_utilities_tests.py, CryptoHashing; the manifest example of
// specification/cryptomatte_specification) and the hash's published values.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "renderer/output/cryptomatte_id.h"

namespace vesper::test {
namespace {

TEST(CryptomatteId, MurmurHash3MatchesPublishedValues) {
  EXPECT_EQ(murmur_hash3_x86_32(""), 0u);
  EXPECT_EQ(murmur_hash3_x86_32("", 1), 0x514e28b7u);
  EXPECT_EQ(murmur_hash3_x86_32("", 0xffffffffu), 0x81f16f39u);
  EXPECT_EQ(murmur_hash3_x86_32("hello"), 0x248bfa47u);
  // Tails of 1, 2 and 3 bytes, one whole block, many blocks.
  EXPECT_EQ(murmur_hash3_x86_32("a"), 0x3c2569b2u);
  EXPECT_EQ(murmur_hash3_x86_32("ab"), 0x9bbfd75fu);
  EXPECT_EQ(murmur_hash3_x86_32("abc"), 0xb3dd93fau);
  EXPECT_EQ(murmur_hash3_x86_32("aaaa", 0x9747b28cu), 0x5a97808au);
  EXPECT_EQ(murmur_hash3_x86_32("Hello, world!", 1234), 0xfaf6cdb3u);
  EXPECT_EQ(murmur_hash3_x86_32("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
}

// The specification's CryptoHashing vectors: name -> float id (compared as
// floats, as its test does after single_precision()).
TEST(CryptomatteId, SpecificationHashVectors) {
  EXPECT_EQ(crypto_id("hello"), float(6.0705627102400005616e-17));
  EXPECT_EQ(crypto_id("cube"), float(-4.08461912519e+15));
  EXPECT_EQ(crypto_id("sphere"), float(2.79018604383e+15));
  EXPECT_EQ(crypto_id("plane"), float(3.66557617593e-11));
  // UTF-8 bytes of "plane" in Bulgarian and of "girl" in German.
  EXPECT_EQ(crypto_id("\xd1\x80\xd0\xb0\xd0\xb2\xd0\xbd\xd0\xb8\xd0\xbd\xd0\xb0"),
            float(-1.3192631212399999468e-25));
  EXPECT_EQ(crypto_id("m\xc3\xa4"
                      "dchen"),
            float(6.2361298211599995797e+25));
}

// The manifest example of the specification: {"bunny":"13851a76", "default":"42c9679f"}.
TEST(CryptomatteId, SpecificationManifestExample) {
  EXPECT_EQ(crypto_hex(crypto_id_bits("bunny")), "13851a76");
  EXPECT_EQ(crypto_hex(crypto_id_bits("default")), "42c9679f");
  EXPECT_EQ(std::bit_cast<uint32_t>(crypto_id("bunny")), 0x13851a76u);
}

// Exponent 0 (zero, denormals) and 255 (inf, NaN) get bit 23 flipped: every
// id is a normal, finite float; other hashes are the float's bits unchanged.
TEST(CryptomatteId, ExponentFixKeepsIdsNormalAndFinite) {
  EXPECT_EQ(crypto_id_bits_of_hash(0x00000000u), 0x00800000u);
  EXPECT_EQ(crypto_id_bits_of_hash(0x80012345u), 0x80812345u);
  EXPECT_EQ(crypto_id_bits_of_hash(0x7f800000u), 0x7f000000u);
  EXPECT_EQ(crypto_id_bits_of_hash(0xffc00001u), 0xff400001u);
  EXPECT_EQ(crypto_id_bits_of_hash(0x3f800000u), 0x3f800000u);
  EXPECT_EQ(crypto_id_bits_of_hash(0x00800000u), 0x00800000u);
  EXPECT_EQ(crypto_id_bits_of_hash(0x7f7fffffu), 0x7f7fffffu);
  EXPECT_EQ(crypto_hex(crypto_id_bits("")), "00800000");  // the empty name hashes to 0
  for (uint32_t h = 0; h < 512; ++h) {                    // every exponent, both signs
    const float f = std::bit_cast<float>(crypto_id_bits_of_hash(h << 23 | 0x1234u));
    EXPECT_TRUE(std::isnormal(f)) << h;
  }
}

TEST(CryptomatteId, MetadataKeyIsTheTypeNamesHashPrefix) {
  EXPECT_EQ(crypto_metadata_key("CryptoObject"), "3ae39a5");
  EXPECT_EQ(crypto_metadata_key("CryptoMaterial"), "be359d6");
}

}  // namespace
}  // namespace vesper::test
