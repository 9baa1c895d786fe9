#include "common/json_reader.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/typo_distance.h"

namespace vesper {
namespace {

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

std::string quoted_list(std::span<const std::string_view> options) {
  std::string out;
  for (size_t i = 0; i < options.size(); ++i) {
    if (i > 0) out += ", ";
    out += '"' + std::string(options[i]) + '"';
  }
  return out;
}

}  // namespace

std::string json_pointer_append(const std::string& path, std::string_view token) {
  std::string out = path + '/';
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string json_pointer_append(const std::string& path, size_t index) {
  return path + '/' + std::to_string(index);
}

std::string describe_json(const nlohmann::json& v) {
  using T = nlohmann::json::value_t;
  switch (v.type()) {
    case T::null:
      return "null";
    case T::boolean:
      return v.get<bool>() ? "true" : "false";
    case T::string: {
      std::string s = v.dump();
      if (s.size() > 60) s = s.substr(0, 57) + "...";
      return "string " + s;
    }
    case T::number_integer:
    case T::number_unsigned:
      return v.dump();
    case T::number_float: {
      const double d = v.get<double>();
      if (std::isnan(d)) return "NaN";
      if (std::isinf(d)) return d > 0 ? "a number too large for a double (inf)" : "-inf";
      return format_number(d);
    }
    case T::object:
      return "an object";
    case T::array:
      return "an array of " + std::to_string(v.size()) + " elements";
    default:
      return "an unsupported value";
  }
}

bool Range::contains(double v) const {
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  const bool lo_inf = std::isinf(lo), hi_inf = std::isinf(hi);
  if (lo_inf && hi_inf) return "a finite number";
  if (hi_inf && lo == 0) return lo_open ? "a positive number" : "a non-negative number";
  if (hi_inf) return std::string("a number ") + (lo_open ? "> " : ">= ") + format_number(lo);
  if (lo_inf) return std::string("a number ") + (hi_open ? "< " : "<= ") + format_number(hi);
  return "a number in " + std::string(lo_open ? "(" : "[") + format_number(lo) + ", " +
         format_number(hi) + (hi_open ? ")" : "]");
}

JsonReader::JsonReader(const nlohmann::json& node, std::string file, std::string path)
    : node_(&node), file_(std::move(file)), path_(std::move(path)) {}

void JsonReader::fail(const std::string& message) const {
  throw JsonError(file_, path_.empty() ? "/" : path_, message);
}

void JsonReader::fail_key(std::string_view key, const std::string& message) const {
  throw JsonError(file_, key_path(key), message);
}

void JsonReader::expect_object() const {
  if (!node_->is_object()) fail("expected an object, got " + describe_json(*node_));
}

void JsonReader::expect_array() const {
  if (!node_->is_array()) fail("expected an array, got " + describe_json(*node_));
}

double JsonReader::as_number(const Range& range) const {
  if (!node_->is_number()) fail("expected " + range.describe() + ", got " + describe_json(*node_));
  const double v = node_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number, got " + describe_json(*node_));
  if (!range.contains(v)) fail("expected " + range.describe() + ", got " + describe_json(*node_));
  return v;
}

int64_t JsonReader::as_integer(int64_t lo, int64_t hi) const {
  const std::string expected =
      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  int64_t v = 0;
  if (node_->is_number_unsigned()) {
    const uint64_t u = node_->get<uint64_t>();
    if (u > uint64_t(hi)) fail("expected " + expected + ", got " + describe_json(*node_));
    v = int64_t(u);
  } else if (node_->is_number_integer()) {
    v = node_->get<int64_t>();
  } else if (node_->is_number_float()) {
    // 64.0 is an integer too; fractional or huge values are not.
    const double d = node_->get<double>();
    if (!std::isfinite(d) || d != std::floor(d) || std::abs(d) > 9007199254740992.0) {
      fail("expected " + expected + ", got " + describe_json(*node_));
    }
    v = int64_t(d);
  } else {
    fail("expected " + expected + ", got " + describe_json(*node_));
  }
  if (v < lo || v > hi) fail("expected " + expected + ", got " + describe_json(*node_));
  return v;
}

uint64_t JsonReader::as_uint64() const {
  if (node_->is_number_unsigned()) return node_->get<uint64_t>();
  return uint64_t(as_integer(0, std::numeric_limits<int64_t>::max()));
}

std::string JsonReader::as_string(bool allow_empty) const {
  if (!node_->is_string()) fail("expected a string, got " + describe_json(*node_));
  std::string s = node_->get<std::string>();
  if (s.empty() && !allow_empty) fail("expected a non-empty string, got \"\"");
  return s;
}

void JsonReader::expect_string(std::string_view expected) const {
  if (!node_->is_string() || node_->get<std::string>() != expected) {
    fail("expected \"" + std::string(expected) + "\", got " + describe_json(*node_));
  }
}

size_t JsonReader::as_enum(std::span<const std::string_view> options) const {
  if (node_->is_string()) {
    const std::string s = node_->get<std::string>();
    for (size_t i = 0; i < options.size(); ++i) {
      if (options[i] == s) return i;
    }
  }
  fail("expected one of " + quoted_list(options) + ", got " + describe_json(*node_));
}

JsonReader JsonReader::element(size_t i) const {
  return JsonReader((*node_)[i], file_, json_pointer_append(path_, i));
}

std::vector<double> JsonReader::as_number_array(const Range& range) const {
  expect_array();
  std::vector<double> out;
  out.reserve(node_->size());
  for (const auto& e : *node_) {
    // Fast path: inline meshes can hold millions of numbers.
    if (e.is_number()) {
      const double v = e.get<double>();
      if (std::isfinite(v) && range.contains(v)) {
        out.push_back(v);
        continue;
      }
    }
    element(out.size()).as_number(range);  // throws with the element's path
  }
  return out;
}

const nlohmann::json* JsonReader::find_key(std::string_view key) {
  if (std::find(known_keys_.begin(), known_keys_.end(), key) == known_keys_.end()) {
    known_keys_.emplace_back(key);
  }
  expect_object();
  const auto it = node_->find(key);
  return it == node_->end() ? nullptr : &*it;
}

const nlohmann::json& JsonReader::require_key(std::string_view key) {
  const nlohmann::json* v = find_key(key);
  if (!v) fail("missing required key '" + std::string(key) + "'");
  return *v;
}

bool JsonReader::has(std::string_view key) { return find_key(key) != nullptr; }

JsonReader JsonReader::child(std::string_view key) {
  return JsonReader(require_key(key), file_, key_path(key));
}

std::optional<JsonReader> JsonReader::optional_child(std::string_view key) {
  const nlohmann::json* v = find_key(key);
  if (!v) return std::nullopt;
  return JsonReader(*v, file_, key_path(key));
}

JsonReader JsonReader::object(std::string_view key) {
  JsonReader r = child(key);
  r.expect_object();
  return r;
}

JsonReader JsonReader::array(std::string_view key) {
  JsonReader r = child(key);
  r.expect_array();
  return r;
}

double JsonReader::number(std::string_view key, const Range& range) {
  return child(key).as_number(range);
}

double JsonReader::number(std::string_view key, double fallback, const Range& range) {
  const auto c = optional_child(key);
  return c ? c->as_number(range) : fallback;
}

int64_t JsonReader::integer(std::string_view key, int64_t lo, int64_t hi) {
  return child(key).as_integer(lo, hi);
}

int64_t JsonReader::integer(std::string_view key, int64_t fallback, int64_t lo, int64_t hi) {
  const auto c = optional_child(key);
  return c ? c->as_integer(lo, hi) : fallback;
}

std::string JsonReader::string(std::string_view key) { return child(key).as_string(); }

size_t JsonReader::enumeration(std::string_view key, std::span<const std::string_view> options) {
  return child(key).as_enum(options);
}

size_t JsonReader::enumeration(std::string_view key, size_t fallback,
                               std::span<const std::string_view> options) {
  const auto c = optional_child(key);
  return c ? c->as_enum(options) : fallback;
}

bool JsonReader::boolean(std::string_view key, bool fallback) {
  const auto c = optional_child(key);
  if (!c) return fallback;
  if (!c->json().is_boolean()) c->fail("expected true or false, got " + describe_json(c->json()));
  return c->json().get<bool>();
}

void JsonReader::allow_keys(std::initializer_list<std::string_view> keys) {
  for (std::string_view k : keys) {
    if (std::find(known_keys_.begin(), known_keys_.end(), k) == known_keys_.end()) {
      known_keys_.emplace_back(k);
    }
  }
  finish();
}

void JsonReader::finish() const {
  expect_object();
  for (const auto& [key, value] : node_->items()) {
    if (std::find(known_keys_.begin(), known_keys_.end(), key) != known_keys_.end()) continue;
    std::string message = "unknown key '" + key + "' (expected one of: ";
    std::string best;
    size_t best_distance = 3;  // hint only for near misses
    for (size_t i = 0; i < known_keys_.size(); ++i) {
      message += (i > 0 ? ", " : "") + known_keys_[i];
      const size_t d = typo_distance(key, known_keys_[i]);
      if (d < best_distance) best_distance = d, best = known_keys_[i];
    }
    message += ")";
    if (!best.empty()) message += "; did you mean '" + best + "'?";
    fail_key(key, message);
  }
}

}  // namespace vesper
