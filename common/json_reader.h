#pragma once
// JsonReader: one node of a JSON document together with its JSON pointer and
// the document's name (its file), so every validation error can name both:
// it throws JsonError "<file>: <json path>: expected ..., got ...". Object
// getters record each key they are asked about; finish() then rejects any
// other key, which is how typos ("radus") are caught instead of silently
// ignored. Used for scenes, composite recipes, job files and partial headers.
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/json_error.h"

namespace vesper {

// Appends one reference token to a JSON pointer, escaping '~' and '/' (RFC 6901).
std::string json_pointer_append(const std::string& path, std::string_view token);
std::string json_pointer_append(const std::string& path, size_t index);

// Short human description of a JSON value for "got ..." in messages.
std::string describe_json(const nlohmann::json& value);

// An interval of accepted numbers; describe() words it for messages.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;

  bool contains(double v) const;
  std::string describe() const;  // "a positive number", "a number in (0, 180)"

  static Range any() { return {}; }
  static Range positive() { return {0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  static Range left_open(double lo, double hi) { return {lo, hi, true, false}; }
  static Range right_open(double lo, double hi) { return {lo, hi, false, true}; }
};

class JsonReader {
 public:
  JsonReader(const nlohmann::json& node, std::string file, std::string path);

  const nlohmann::json& json() const { return *node_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  std::string key_path(std::string_view key) const { return json_pointer_append(path_, key); }

  // Throw JsonError at this node / at its `key`.
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail_key(std::string_view key, const std::string& message) const;

  // This node as a value (throws unless it has the expected type and range).
  void expect_object() const;
  void expect_array() const;
  double as_number(const Range& range = Range::any()) const;
  int64_t as_integer(int64_t lo, int64_t hi) const;
  uint64_t as_uint64() const;
  std::string as_string(bool allow_empty = false) const;
  // This node must be the string `expected` (a format tag such as "vesper-scene/1").
  void expect_string(std::string_view expected) const;
  // Index into `options`; the message lists them all.
  size_t as_enum(std::span<const std::string_view> options) const;

  // Array elements (this node must be an array).
  size_t size() const { return node_->size(); }
  JsonReader element(size_t i) const;
  // A flat array of numbers, validated without building a reader per element.
  std::vector<double> as_number_array(const Range& range = Range::any()) const;

  // Object keys. Every function below records `key` as known to this object.
  bool has(std::string_view key);
  JsonReader child(std::string_view key);  // required, any type
  std::optional<JsonReader> optional_child(std::string_view key);
  JsonReader object(std::string_view key);  // required object
  JsonReader array(std::string_view key);   // required array

  double number(std::string_view key, const Range& range = Range::any());
  double number(std::string_view key, double fallback, const Range& range = Range::any());
  int64_t integer(std::string_view key, int64_t lo, int64_t hi);
  int64_t integer(std::string_view key, int64_t fallback, int64_t lo, int64_t hi);
  std::string string(std::string_view key);
  size_t enumeration(std::string_view key, std::span<const std::string_view> options);
  size_t enumeration(std::string_view key, size_t fallback,
                     std::span<const std::string_view> options);
  bool boolean(std::string_view key, bool fallback);

  // Records the keys this object may hold and rejects any other key now, so a
  // typo is reported as unknown before its absence would be reported as missing.
  void allow_keys(std::initializer_list<std::string_view> keys);
  // Rejects keys of this object that no getter (or allow_keys) asked about.
  void finish() const;

 private:
  const nlohmann::json* find_key(std::string_view key);
  const nlohmann::json& require_key(std::string_view key);

  const nlohmann::json* node_;
  std::string file_, path_;
  std::vector<std::string> known_keys_;  // in the order the parser asked for them
};

}  // namespace vesper
