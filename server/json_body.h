#pragma once
// Parsing and validating JSON request bodies. Every error is an ApiError 400
// naming the JSON path (RFC 6901 pointer such as "/frames") and what was
// expected there; unknown keys are rejected, so a typo ("sample_per_task")
// is an error rather than a silently ignored default.
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace vesper {

nlohmann::json parse_json_body(const std::string& body);

// A view of one JSON object in a request body.
class JsonObject {
 public:
  // Throws unless `j` is an object whose keys are all in `allowed`.
  JsonObject(const nlohmann::json& j, std::string path, std::initializer_list<const char*> allowed);

  bool has(const char* key) const;
  std::string path(const char* key) const { return path_ + "/" + key; }
  const nlohmann::json& at(const char* key) const;

  std::string string(const char* key) const;  // required, non-empty
  std::optional<std::string> opt_string(const char* key) const;
  int64_t integer(const char* key, int64_t def, int64_t min, int64_t max) const;  // optional
  double number(const char* key, double def, double min, double max) const;       // optional

 private:
  const nlohmann::json& j_;
  std::string path_;
};

}  // namespace vesper
