#pragma once
// Declares a message's nlohmann::json conversions (found by ADL: `json j = m;`,
// `j.get<T>()`). Defined in the message's .cpp from its table of fields.
#include <nlohmann/json_fwd.hpp>

#define VESPER_JSON_CONVERSIONS(Type)             \
  void to_json(nlohmann::json& j, const Type& m); \
  void from_json(const nlohmann::json& j, Type& m)
