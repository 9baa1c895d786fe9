// UTF-8 repair and cutting at character boundaries (messages and log tails
// that go into JSON).
#include "common/utf8.h"

#include <gtest/gtest.h>
namespace vesper {
namespace {

TEST(Utf8, WellFormedCharactersAndTheMalformedOnes) {
  EXPECT_TRUE(is_valid_utf8("plain ascii"));
  EXPECT_TRUE(is_valid_utf8("é ü 漢 🎞"));
  EXPECT_TRUE(is_valid_utf8(""));
  for (const char* bad :
       {"\xff", "\xc3", "a\x80", "\xc0\xaf" /* overlong '/' */, "\xe0\x80\xaf",
        "\xed\xa0\x80" /* surrogate */, "\xf4\x90\x80\x80" /* > U+10FFFF */, "\xe6\xbc" /* cut */})
    EXPECT_FALSE(is_valid_utf8(bad)) << bad;
  EXPECT_EQ(utf8_character_length("漢", 0), 3u);
  EXPECT_EQ(utf8_character_length("🎞", 0), 4u);
  EXPECT_EQ(utf8_character_length("漢", 1), 0u);
}

TEST(Utf8, SafeReplacesInvalidBytesAndCutsAtCharacterBoundaries) {
  EXPECT_EQ(utf8_safe("a\xff"
                      "b"),
            "a\xEF\xBF\xBD"
            "b");
  EXPECT_EQ(utf8_safe("\xc3"), "\xEF\xBF\xBD");
  // "é" is 2 bytes: a cut at 3 bytes keeps "aé", at 2 keeps "a".
  EXPECT_EQ(utf8_safe("aéb", 3), "aé");
  EXPECT_EQ(utf8_safe("aéb", 2), "a");
  EXPECT_EQ(utf8_safe("漢字", 5), "漢");
  EXPECT_EQ(utf8_safe("abc", 0), "");
  for (size_t n = 0; n < 12; ++n) EXPECT_TRUE(is_valid_utf8(utf8_safe("a漢🎞é\xff", n))) << n;
}

TEST(Utf8, TailStartsAtACharacterBoundary) {
  EXPECT_EQ(utf8_tail("abc", 10), "abc");
  EXPECT_EQ(utf8_tail("a漢", 2), "");  // the last 2 bytes are the end of one character
  EXPECT_EQ(utf8_tail("a漢", 3), "漢");
  EXPECT_EQ(utf8_tail("x漢字", 4), "字");
  const std::string log = std::string(100, 'x') + "漢字🎞";
  for (size_t n = 0; n < 20; ++n) {
    const std::string t = utf8_tail(log, n);
    EXPECT_TRUE(is_valid_utf8(t)) << n;
    EXPECT_LE(t.size(), n);
    EXPECT_EQ(log.compare(log.size() - t.size(), t.size(), t), 0) << n;
  }
}

}  // namespace
}  // namespace vesper
