#include "common/json_parse.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <vector>

#include "common/json_error.h"
#include "common/json_reader.h"
#include "common/utf8.h"

namespace vesper {
namespace {

// The parse callback that rejects a key seen twice in one object and
// nesting deeper than kMaxJsonDepth.
class StructureCheck {
 public:
  explicit StructureCheck(std::string file) : file_(std::move(file)) {}
  bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (stack_.size() >= size_t(kMaxJsonDepth))
          throw JsonError(
              file_, path(),
              "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        stack_.push_back({event == E::array_start, 0, {}, {}});
        break;
      case E::key: {
        Frame& top = stack_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second) {
          throw JsonError(file_, path(), "duplicate key '" + top.key + "'");
        }
        break;
      }
      case E::object_end:
      case E::array_end:
        stack_.pop_back();
        [[fallthrough]];
      case E::value:
        if (!stack_.empty() && stack_.back().is_array) ++stack_.back().index;
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array;
    size_t index;
    std::string key;
    std::set<std::string> keys;
  };
  std::string path() const {
    std::string p;
    for (const Frame& f : stack_) {
      p = f.is_array ? json_pointer_append(p, f.index) : json_pointer_append(p, f.key);
    }
    return p;
  }
  std::string file_;
  std::vector<Frame> stack_;
};

// nlohmann reports a byte offset; people need line and column.
std::string at_line_column(const std::string& text, size_t offset) {
  const size_t end = std::min(offset, text.size());
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') ++line, line_start = i + 1;
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(end - line_start + 1);
}

// nlohmann's what() minus its "[json.exception.x.N] ... column C: " prefix;
// it quotes what it last read, which may be bytes that are not UTF-8.
std::string nlohmann_detail(const nlohmann::json::exception& e) {
  std::string detail = e.what();
  if (const size_t bracket = detail.find("] "); bracket != std::string::npos) {
    detail = detail.substr(bracket + 2);
  }
  if (detail.rfind("parse error", 0) == 0) {
    if (const size_t colon = detail.find(": "); colon != std::string::npos) {
      detail = detail.substr(colon + 2);
    }
  }
  return utf8_safe(detail);
}

}  // namespace

nlohmann::json parse_json(const std::string& text, const std::string& file) {
  try {
    return nlohmann::json::parse(text, StructureCheck(file));
  } catch (const nlohmann::json::parse_error& e) {
    throw JsonError(file, "",
                    "invalid JSON at " + at_line_column(text, e.byte > 0 ? e.byte - 1 : 0) + ": " +
                        nlohmann_detail(e));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond the double range (1e999) carries no position; find its text.
    std::string where = "invalid JSON";
    const std::string what = e.what();
    const size_t q = what.find('\'');
    if (q != std::string::npos && what.back() == '\'') {
      const size_t at = text.find(what.substr(q + 1, what.size() - q - 2));
      if (at != std::string::npos) where += " at " + at_line_column(text, at);
    }
    throw JsonError(file, "",
                    where + ": " + nlohmann_detail(e) + " (numbers must be finite doubles)");
  }
}

std::string read_text_file(const std::filesystem::path& file, std::string_view what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw JsonError(file.string(), "", "cannot open " + std::string(what));
  return std::string(std::istreambuf_iterator<char>(in), {});
}

nlohmann::json read_json_file(const std::filesystem::path& file, std::string_view what) {
  return parse_json(read_text_file(file, what), file.string());
}

}  // namespace vesper
