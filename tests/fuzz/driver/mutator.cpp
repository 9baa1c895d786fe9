// Mutations for the fuzz driver (mutator.h).
#include "tests/fuzz/driver/mutator.h"

#include <algorithm>
#include <set>

#include <nlohmann/json.hpp>

namespace vesper::fuzz {
namespace {

// JSON text the parsers' edges live at: the double range, the int range,
// subnormals, sizes just past a limit.
const char* const kNumbers[] = {"0",
                                "-0",
                                "1",
                                "-1",
                                "0.5",
                                "2",
                                "3",
                                "7",
                                "1e400",
                                "-1e400",
                                "1e308",
                                "-1e308",
                                "1.7976931348623157e308",
                                "1e-310",
                                "-1e-310",
                                "4.9e-324",
                                "1e-45",
                                "3.4e38",
                                "3.5e38",
                                "2147483647",
                                "2147483648",
                                "-2147483648",
                                "-2147483649",
                                "4294967296",
                                "9223372036854775807",
                                "9223372036854775808",
                                "-9223372036854775809",
                                "18446744073709551615",
                                "18446744073709551616",
                                "1e15",
                                "1048576",
                                "1048577",
                                "65536",
                                "65537",
                                "1e6",
                                "1e-6",
                                "100",
                                "101",
                                "180",
                                "360",
                                "1e9",
                                "99999",
                                "100001",
                                "2592001"};

// Strings a parser may trip over: not-quite numbers, control characters,
// invalid UTF-8, paths that leave their folder, frame patterns and ranges.
const char* const kStrings[] = {
    R"("")",
    R"("NaN")",
    R"("nan")",
    R"("inf")",
    R"("-inf")",
    R"("Infinity")",
    R"("1e400")",
    R"("\u0000")",
    R"("\u001b[31mred")",
    "\"\xff\xfe\"",
    "\"\xc3\"",
    "\"\xed\xa0\x80\"",
    R"("../../etc/passwd")",
    R"("/etc/passwd")",
    R"("/dev/zero")",
    R"("####")",
    R"("a/b")",
    R"(".")",
    R"("..")",
    R"("-2147483648-2147483647x4096")",
    R"("1-1000000")",
    R"("0-2147483647")",
    R"("1-2147483647x2")",
    R"("1,,2")",
    R"("1-10x0")",
    R"("-5--1")",
    R"("scene.json")",
    R"("cloud.vdb")",
    R"("sky.exr")",
    R"("out/x.####.png")",
    R"("frame.####.exr")",
    R"("a\nb")",
    R"("0000000000000000000000000000000000000000000000000000000000000000")"};

// Values of every JSON type, including ones no reader expects.
const char* const kShapes[] = {"null",
                               "true",
                               "false",
                               "{}",
                               "[]",
                               "[0]",
                               "[1e400,0,0]",
                               "[0,0,0]",
                               "[1,1,1]",
                               "[1e308,1e308,1e308]",
                               "[-1e308,1e308,0]",
                               "[1e-310,1e-310,1e-310]",
                               "[0,0,0,0]",
                               "{\"a\":1}",
                               "[[[]]]",
                               "[\"beauty\"]",
                               "[1,2]",
                               "{\"\":0}"};

// Outside any string, how deep arrays and objects nest (the mutator only
// parses inputs far from nlohmann's recursive dump's limits).
int nesting_depth(const std::string& s) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

std::string deep(size_t n, bool objects) {
  std::string s;
  for (size_t i = 0; i < n; ++i) s += objects ? "{\"a\":" : "[";
  s += "0";
  for (size_t i = 0; i < n; ++i) s += objects ? '}' : ']';
  return s;
}

struct Node {
  nlohmann::json* value;
  nlohmann::json* parent;  // null for the root
  std::string key;         // in an object parent
  size_t index = 0;        // in an array parent
};

std::vector<Node> nodes_of(nlohmann::json& root) {
  std::vector<Node> nodes{{&root, nullptr, {}, 0}};
  for (size_t i = 0; i < nodes.size(); ++i) {
    nlohmann::json* v = nodes[i].value;
    if (v->is_object())
      for (auto it = v->begin(); it != v->end(); ++it) nodes.push_back({&*it, v, it.key(), 0});
    else if (v->is_array())
      for (size_t k = 0; k < v->size(); ++k) nodes.push_back({&(*v)[k], v, {}, k});
  }
  return nodes;
}

constexpr const char* kSlot = "\x01vesper-fuzz-slot\x01";
constexpr const char* kSlotText = "\"\\u0001vesper-fuzz-slot\\u0001\"";

std::string dump(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

Mutator::Mutator(uint64_t seed, std::vector<std::string> dictionary)
    : rng_(seed), dictionary_(std::move(dictionary)) {}

std::string Mutator::raw_value() {
  switch (next(8)) {
    case 0:
    case 1:
    case 2:
      return kNumbers[next(std::size(kNumbers))];
    case 3:
      return kStrings[next(std::size(kStrings))];
    case 4:
      return kShapes[next(std::size(kShapes))];
    case 5: {
      const size_t depths[] = {99, 100, 101, 1000, 100000};
      return deep(depths[next(std::size(depths))], next(2) == 0);
    }
    case 6:
      return "\"" + std::string(size_t(1) << (4 + next(14)), "a#/.\\"[next(4)]) + "\"";
    default:
      if (dictionary_.empty()) return "0";
      return dump(nlohmann::json(dictionary_[next(dictionary_.size())]));
  }
}

std::string Mutator::mutate_json(const std::string& s, const std::vector<std::string>& others) {
  if (s.size() > (1u << 20) || nesting_depth(s) > 200) return {};
  nlohmann::json doc = nlohmann::json::parse(s, nullptr, false);
  if (doc.is_discarded()) return {};
  std::vector<Node> nodes = nodes_of(doc);
  Node& n = nodes[next(nodes.size())];
  std::string raw;  // the node's replacement, as JSON text
  switch (next(7)) {
    case 0:
    case 1:
      raw = raw_value();
      break;
    case 2: {  // another node, of this document or another input
      nlohmann::json other =
          others.empty() ? nlohmann::json()
                         : nlohmann::json::parse(others[next(others.size())], nullptr, false);
      if (other.is_discarded() || other.is_null() || nesting_depth(dump(other)) > 200) other = doc;
      std::vector<Node> pick = nodes_of(other);
      raw = dump(*pick[next(pick.size())].value);
      break;
    }
    case 3:  // remove the node
      if (n.parent && n.parent->is_object())
        n.parent->erase(n.key);
      else if (n.parent)
        n.parent->erase(n.index);
      return dump(doc);
    case 4:  // a key more (or twice)
      if (n.value->is_object()) {
        const std::string key = next(3) == 0 && !n.value->empty() ? n.value->begin().key()
                                : dictionary_.empty()             ? "x"
                                                      : dictionary_[next(dictionary_.size())];
        const std::string rest = dump(*n.value).substr(1);
        raw = "{" + dump(nlohmann::json(key)) + ":" + raw_value() + (rest == "}" ? "" : ",") + rest;
        break;
      }
      [[fallthrough]];
    case 5:  // a longer array
      if (n.value->is_array() && !n.value->empty()) {
        const nlohmann::json e = (*n.value)[next(n.value->size())];
        const size_t copies = size_t(1) << next(12);
        for (size_t i = 0; i < copies && dump(*n.value).size() < (1u << 18); ++i)
          n.value->push_back(e);
        return dump(doc);
      }
      [[fallthrough]];
    default:                             // a number nudged
      if (n.value->is_number_integer())  // +-1, wrapping (no signed overflow)
        raw = std::to_string(
            static_cast<long long>(n.value->get<unsigned long long>() + next(3) - 1));
      else if (n.value->is_number())
        raw = dump(*n.value) + (next(2) ? "e300" : "0000");
      else
        raw = raw_value();
  }
  *n.value = kSlot;
  std::string text = dump(doc);
  const size_t at = text.find(kSlotText);
  if (at == std::string::npos) return text;
  return text.replace(at, std::string(kSlotText).size(), raw);
}

std::string Mutator::mutate_bytes(std::string s, const std::vector<std::string>& others) {
  const size_t at = next(s.size() + 1);
  switch (next(8)) {
    case 0:
      if (!s.empty()) s[at % s.size()] ^= char(1u << next(8));
      break;
    case 1:
      if (!s.empty()) s[at % s.size()] = "{}[],:\"\\0123456789eE.-+ \x00\xff\x80"[next(27)];
      break;
    case 2:
      for (uint64_t i = 0, n = 1 + next(8); i < n; ++i) s.insert(s.begin() + at, char(next(256)));
      break;
    case 3:
      s.erase(at, 1 + next(64));
      break;
    case 4:
      if (!s.empty()) {
        const size_t from = next(s.size());
        s.insert(next(s.size()), s.substr(from, 1 + next(64)));
      }
      break;
    case 5:
      s.insert(
          at, dictionary_.empty() || next(2) ? raw_value() : dictionary_[next(dictionary_.size())]);
      break;
    case 6:
      if (!others.empty()) {
        const std::string& o = others[next(others.size())];
        s = s.substr(0, at) + o.substr(next(o.size() + 1));
      }
      break;
    default: {  // a run of digits replaced by an edge number
      const size_t d = s.find_first_of("0123456789", at);
      if (d == std::string::npos) break;
      const size_t e = s.find_first_not_of("0123456789.eE+-", d);
      s.replace(d, (e == std::string::npos ? s.size() : e) - d,
                kNumbers[next(std::size(kNumbers))]);
    }
  }
  return s;
}

std::string Mutator::mutate(const std::string& input, const std::vector<std::string>& others) {
  std::string s = input;
  for (uint64_t i = 0, n = 1 + next(4); i < n; ++i) {
    std::string j = next(3) != 0 ? mutate_json(s, others) : std::string();
    s = j.empty() ? mutate_bytes(std::move(s), others) : std::move(j);
    if (s.size() > (1u << 21)) s.resize(1u << 21);
  }
  return s;
}

std::vector<std::string> json_dictionary(const std::vector<std::string>& inputs) {
  std::set<std::string> words;
  for (const std::string& in : inputs) {
    nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
    if (doc.is_discarded()) continue;
    for (const Node& n : nodes_of(doc)) {
      if (n.parent && n.parent->is_object()) words.insert(n.key);
      if (n.value->is_string()) words.insert(n.value->get<std::string>());
    }
  }
  return {words.begin(), words.end()};
}

}  // namespace vesper::fuzz
