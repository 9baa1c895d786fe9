// Control characters in names: found (refused where a name enters the farm)
// and escaped (where one is printed).
#include "common/control_characters.h"

#include <gtest/gtest.h>

#include <string>

namespace vesper {
namespace {

TEST(ControlCharacters, AreFoundAndNamed) {
  EXPECT_EQ(control_character_problem("night-room ünïcode 漢"), "");
  EXPECT_EQ(control_character_problem("a\x1b[31mred"), "contains a control character (U+001B)");
  EXPECT_EQ(control_character_problem("two\nlines"), "contains a control character (U+000A)");
  EXPECT_EQ(control_character_problem("del\x7f"), "contains a control character (U+007F)");
  EXPECT_EQ(control_character_problem("csi\xc2\x9b"), "contains a control character (U+009B)");
  EXPECT_EQ(control_character_problem(std::string("nul\0x", 5)),
            "contains a control character (U+0000)");
}

TEST(ControlCharacters, AreEscapedForTerminals) {
  EXPECT_EQ(escape_control_characters("plain é"), "plain é");
  EXPECT_EQ(escape_control_characters("a\x1b[2Jb\nc\rd\te"), "a\\x1b[2Jb\\nc\\rd\\te");
  EXPECT_EQ(escape_control_characters("back\\slash"), "back\\\\slash");
  EXPECT_EQ(escape_control_characters("c1\xc2\x9b!"), "c1\\u009b!");
  EXPECT_EQ(escape_control_characters("bad\xff"), "bad\\xff");
  EXPECT_EQ(control_character_problem(escape_control_characters("\x01\x1b\x7f\xc2\x85\xff")), "");
}

}  // namespace
}  // namespace vesper
