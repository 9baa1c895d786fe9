#pragma once
// Text to JSON with errors people can act on: JsonError naming the file and
// the line and column of a syntax error, or the JSON path of a duplicated key
// (nlohmann would keep the last one silently; in a hand-written file a
// duplicate is almost always a mistake). Every JSON document Vesper reads
// from people or the network (scenes, recipes, job files, suites, API bodies)
// goes through parse_json, so its depth limit is the one limit everywhere.
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace vesper {

// Deepest nesting of arrays and objects accepted. Real documents nest a
// handful of levels; the limit keeps every recursive use of a parsed value
// (copies, dumps, readers) far from the stack's end (a recipe nested 100 000
// deep crashed `vesper comp`).
inline constexpr int kMaxJsonDepth = 100;

// `file` names the document in messages. Throws JsonError for invalid JSON, a
// number beyond the double range (1e999), a duplicated key, or arrays and
// objects nested deeper than kMaxJsonDepth (refused while parsing, before
// anything deep is built).
nlohmann::json parse_json(const std::string& text, const std::string& file);

// The whole file; JsonError "<file>: cannot open <what>" if it cannot be read
// (`what` says which file it was meant to be, e.g. "the scene file").
std::string read_text_file(const std::filesystem::path& file, std::string_view what);

// read_text_file + parse_json.
nlohmann::json read_json_file(const std::filesystem::path& file, std::string_view what);

}  // namespace vesper
