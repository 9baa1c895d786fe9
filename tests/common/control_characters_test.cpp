// Control characters in names: found (refused where a name enters the farm)
// and escaped (where one is printed).
#include "common/control_characters.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <utility>

namespace vesper {
namespace {

// Each name with the code point of its first control character (-1: none).
TEST(ControlCharacters, AreFoundAndNamed) {
  const std::pair<std::string, int> cases[] = {
      {"night-room ünïcode 漢", -1}, {"a\x1b[31mred", 0x1b},
      {"two\nlines", 0x0a},          {"del\x7f", 0x7f},
      {"csi\xc2\x9b", 0x9b},         {std::string("nul\0x", 5), 0}};
  for (const auto& [name, code] : cases) {
    char expected[64] = "";
    if (code >= 0)
      std::snprintf(expected, sizeof expected, "contains a control character (U+%04X)", code);
    EXPECT_EQ(control_character_problem(name), expected) << name;
  }
}

TEST(ControlCharacters, AreEscapedForTerminals) {
  const std::pair<std::string, std::string> cases[] = {
      {"plain é", "plain é"},
      {"a\x1b[2Jb\nc\rd\te", "a\\x1b[2Jb\\nc\\rd\\te"},
      {"back\\slash", "back\\\\slash"},
      {"c1\xc2\x9b!", "c1\\u009b!"},
      {"bad\xff", "bad\\xff"}};
  for (const auto& [raw, shown] : cases) EXPECT_EQ(escape_control_characters(raw), shown) << raw;
  EXPECT_EQ(control_character_problem(escape_control_characters("\x01\x1b\x7f\xc2\x85\xff")), "");
}

}  // namespace
}  // namespace vesper
