// The validating JSON reader and parser: every error names the file, the JSON
// path and what was expected (the style of scenes, recipes, job files and
// partial headers).
#include "common/json_reader.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "common/json_parse.h"
#include "common/utf8.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

using nlohmann::json;

// what() of the JsonError `f` throws, or a note that it threw none.
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const JsonError& e) {
    return e.what();
  }
  return "(no JsonError)";
}

TEST(JsonError, NamesFilePathAndMessage) {
  const JsonError e("f.json", "/a/0", "expected a string, got 1");
  EXPECT_STREQ(e.what(), "f.json: /a/0: expected a string, got 1");
  EXPECT_EQ(e.file(), "f.json");
  EXPECT_EQ(e.json_path(), "/a/0");
  EXPECT_EQ(e.message(), "expected a string, got 1");
  EXPECT_STREQ(JsonError("f.json", "", "cannot open the file").what(),
               "f.json: cannot open the file");
}

TEST(JsonPointer, EscapesTildeAndSlash) {
  EXPECT_EQ(json_pointer_append("", "a/b~c"), "/a~1b~0c");
  EXPECT_EQ(json_pointer_append("/x", size_t(3)), "/x/3");
}

TEST(JsonReader, ValuesAreCheckedWithTheirPath) {
  const json doc = json::parse(R"({"n": -1, "i": 2.5, "s": "", "list": [1, "x"], "b": 1,
                                  "e": "cube", "f": "v/2"})");
  JsonReader r(doc, "f.json", "");
  EXPECT_EQ(error_of([&] { r.number("n", Range::positive()); }),
            "f.json: /n: expected a positive number, got -1");
  EXPECT_EQ(error_of([&] { r.integer("i", 0, 10); }),
            "f.json: /i: expected an integer in [0, 10], got 2.5");
  EXPECT_EQ(error_of([&] { r.string("s"); }), "f.json: /s: expected a non-empty string, got \"\"");
  EXPECT_EQ(error_of([&] { r.child("list").as_number_array(); }),
            "f.json: /list/1: expected a finite number, got string \"x\"");
  EXPECT_EQ(error_of([&] { r.boolean("b", false); }), "f.json: /b: expected true or false, got 1");
  constexpr std::string_view kShapes[] = {"sphere", "quad"};
  EXPECT_EQ(error_of([&] { r.enumeration("e", kShapes); }),
            "f.json: /e: expected one of \"sphere\", \"quad\", got string \"cube\"");
  EXPECT_EQ(error_of([&] { r.child("f").expect_string("v/1"); }),
            "f.json: /f: expected \"v/1\", got string \"v/2\"");
  EXPECT_EQ(error_of([&] { r.child("missing"); }), "f.json: /: missing required key 'missing'");
  EXPECT_EQ(error_of([&] { r.array("n"); }), "f.json: /n: expected an array, got -1");
}

TEST(JsonReader, DefaultsApplyOnlyToAbsentKeys) {
  const json doc = json::parse(R"({"x": 3})");
  JsonReader r(doc, "f.json", "");
  EXPECT_EQ(r.number("x", 1.0), 3.0);
  EXPECT_EQ(r.number("y", 1.0), 1.0);
  EXPECT_EQ(r.integer("z", 7, 0, 10), 7);
  EXPECT_TRUE(r.boolean("w", true));
  EXPECT_FALSE(r.has("v"));
  EXPECT_NO_THROW(r.finish());
}

TEST(JsonReader, UnknownKeysAreRejectedWithANearMiss) {
  const json doc = json::parse(R"({"radus": 1})");
  JsonReader r(doc, "f.json", "/shapes/0");
  EXPECT_EQ(error_of([&] {
              r.allow_keys({"type", "radius"});
            }),
            "f.json: /shapes/0/radus: unknown key 'radus' (expected one of: type, radius); did "
            "you mean 'radius'?");
  const json far = json::parse(R"({"colour": 1})");
  JsonReader f(far, "f.json", "");
  f.has("radius");
  EXPECT_EQ(error_of([&] { f.finish(); }),
            "f.json: /colour: unknown key 'colour' (expected one of: radius)");
}

TEST(JsonReader, IntegersKeepTheirFullRange) {
  const json doc = json::parse(R"({"seed": 18446744073709551615, "big": 1e300, "whole": 64.0})");
  JsonReader r(doc, "f.json", "");
  EXPECT_EQ(r.child("seed").as_uint64(), 18446744073709551615ull);
  EXPECT_EQ(r.integer("whole", 0, 100), 64);
  EXPECT_EQ(error_of([&] { r.integer("big", 0, 100); }),
            "f.json: /big: expected an integer in [0, 100], got 1e+300");
}

TEST(Range, DescribesItself) {
  EXPECT_EQ(Range::any().describe(), "a finite number");
  EXPECT_EQ(Range::non_negative().describe(), "a non-negative number");
  EXPECT_EQ(Range::open(0, 180).describe(), "a number in (0, 180)");
  EXPECT_EQ(Range::right_open(0, 1).describe(), "a number in [0, 1)");
  EXPECT_TRUE(Range::left_open(0, 1).contains(1));
  EXPECT_FALSE(Range::left_open(0, 1).contains(0));
}

TEST(ParseJson, SyntaxErrorsNameLineAndColumn) {
  const std::string err = error_of([] { parse_json("{\n  \"a\": 1,\n}", "f.json"); });
  EXPECT_EQ(err.rfind("f.json: invalid JSON at line 3, column 1: ", 0), 0u) << err;
  EXPECT_EQ(error_of([] { parse_json("", "f.json"); })
                .rfind("f.json: invalid JSON at line 1, "
                       "column 1",
                       0),
            0u);
  const std::string big = error_of([] { parse_json("{\n \"x\": 1e999}", "f.json"); });
  EXPECT_NE(big.find("line 2, column 7: number overflow parsing '1e999'"), std::string::npos)
      << big;
}

TEST(ParseJson, DuplicateKeysAreRejectedAtTheirPath) {
  EXPECT_EQ(error_of([] { parse_json(R"({"a": [{"r": 1, "r": 2}]})", "f.json"); }),
            "f.json: /a/0/r: duplicate key 'r'");
  EXPECT_EQ(parse_json(R"({"a": [{"r": 1}, {"r": 2}]})", "f.json")["a"][1]["r"], 2);
}

// One depth limit for every document, checked while parsing: nothing deep is
// ever built (a recipe nested 100 000 deep overflowed the stack when copied).
TEST(ParseJson, NestingDeeperThanTheLimitIsRefused) {
  const auto nested = [](int depth) {
    return std::string(size_t(depth), '[') + std::string(size_t(depth), ']');
  };
  EXPECT_TRUE(parse_json(nested(kMaxJsonDepth), "f.json").is_array());
  const std::string err = error_of([&] { parse_json(nested(kMaxJsonDepth + 1), "f.json"); });
  EXPECT_NE(err.find("nested deeper than 100 levels"), std::string::npos) << err;
  EXPECT_EQ(err.rfind("f.json: /0/0/0", 0), 0u) << err;
  for (const std::string& deep : {nested(100000), "{\"a\": " + nested(100000) + "}",
                                  std::string(100000, '[') /* unterminated */}) {
    const std::string e = error_of([&] { parse_json(deep, "deep.json"); });
    EXPECT_NE(e.find("nested deeper than"), std::string::npos) << e.substr(0, 200);
  }
  std::string objects;
  for (int i = 0; i < 100000; ++i) objects += "{\"k\":";
  EXPECT_NE(error_of([&] { parse_json(objects, "o.json"); }).find("nested deeper"),
            std::string::npos);
}

// Syntax errors quote what the parser read last: bytes that are not UTF-8
// are replaced, so the message can be sent as JSON (a 500 before).
TEST(ParseJson, ErrorsAboutInvalidUtf8AreValidUtf8) {
  const std::string err = error_of([] { parse_json("{\"name\": \"a\xff\xfe\"}", "f.json"); });
  EXPECT_NE(err.find("invalid JSON"), std::string::npos) << err;
  EXPECT_TRUE(is_valid_utf8(err)) << err;
}

TEST(ParseJson, FilesThatCannotBeReadAreNamed) {
  const test::TempDir dir("common");
  EXPECT_EQ(error_of([&] { read_json_file(dir / "none.json", "the recipe file"); }),
            (dir / "none.json").string() + ": cannot open the recipe file");
  std::ofstream(dir / "ok.json") << R"({"k": [1, 2]})";
  EXPECT_EQ(read_json_file(dir / "ok.json", "x")["k"][1], 2);
}

}  // namespace
}  // namespace vesper
