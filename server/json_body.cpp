#include "server/json_body.h"

#include "server/api_error.h"

namespace vesper {

using nlohmann::json;

json parse_json_body(const std::string& body) {
  try {
    return json::parse(body);
  } catch (const json::parse_error& e) {
    throw ApiError(400, std::string("request body is not valid JSON: ") + e.what(), "");
  }
}

namespace {
const char* type_name(const json& j) { return j.type_name(); }
// RFC 6901 escaping of one reference token.
std::string escape(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}
}  // namespace

JsonObject::JsonObject(const json& j, std::string path, std::initializer_list<const char*> allowed)
    : j_(j), path_(std::move(path)) {
  if (!j.is_object())
    throw ApiError(400, std::string("expected an object, got ") + type_name(j),
                   path_.empty() ? "" : path_);
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw ApiError(400, "unknown key '" + key + "' (expected one of: " + list + ")",
                     path_ + "/" + escape(key));
    }
  }
}

bool JsonObject::has(const char* key) const { return j_.contains(key); }

const json& JsonObject::at(const char* key) const {
  if (!has(key)) throw ApiError(400, std::string("missing required key '") + key + "'", path(key));
  return j_.at(key);
}

std::string JsonObject::string(const char* key) const {
  const json& v = at(key);
  if (!v.is_string())
    throw ApiError(400, std::string("expected a string, got ") + type_name(v), path(key));
  if (v.get_ref<const std::string&>().empty())
    throw ApiError(400, "expected a non-empty string", path(key));
  return v.get<std::string>();
}

std::optional<std::string> JsonObject::opt_string(const char* key) const {
  if (!has(key)) return std::nullopt;
  const json& v = j_.at(key);
  if (!v.is_string())
    throw ApiError(400, std::string("expected a string, got ") + type_name(v), path(key));
  return v.get<std::string>();
}

int64_t JsonObject::integer(const char* key, int64_t def, int64_t min, int64_t max) const {
  if (!has(key)) return def;
  const json& v = j_.at(key);
  if (!v.is_number_integer())
    throw ApiError(400, std::string("expected an integer, got ") + type_name(v), path(key));
  // Unsigned values above int64 range arrive as number_unsigned.
  if (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(max))
    throw ApiError(400,
                   "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                       "], got " + v.dump(),
                   path(key));
  const int64_t x = v.get<int64_t>();
  if (x < min || x > max)
    throw ApiError(400,
                   "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                       "], got " + std::to_string(x),
                   path(key));
  return x;
}

double JsonObject::number(const char* key, double def, double min, double max) const {
  if (!has(key)) return def;
  const json& v = j_.at(key);
  if (!v.is_number())
    throw ApiError(400, std::string("expected a number, got ") + type_name(v), path(key));
  const double x = v.get<double>();
  if (!(x >= min && x <= max))
    throw ApiError(400,
                   "expected a number in [" + std::to_string(min) + ", " + std::to_string(max) +
                       "], got " + v.dump(),
                   path(key));
  return x;
}

}  // namespace vesper
