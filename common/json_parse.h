#pragma once
// Text to JSON with errors people can act on: JsonError naming the file and
// the line and column of a syntax error, or the JSON path of a duplicated key
// (nlohmann would keep the last one silently; in a hand-written file a
// duplicate is almost always a mistake).
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace vesper {

// `file` names the document in messages. Throws JsonError for invalid JSON, a
// number beyond the double range (1e999) or a duplicated key.
nlohmann::json parse_json(const std::string& text, const std::string& file);

// The whole file; JsonError "<file>: cannot open <what>" if it cannot be read
// (`what` says which file it was meant to be, e.g. "the scene file").
std::string read_text_file(const std::filesystem::path& file, std::string_view what);

// read_text_file + parse_json.
nlohmann::json read_json_file(const std::filesystem::path& file, std::string_view what);

}  // namespace vesper
