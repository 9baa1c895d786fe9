#include "protocol/error_body.h"

#include <nlohmann/json.hpp>

#include "protocol/fields.h"

namespace vesper::protocol {

void to_json(nlohmann::json& j, const ErrorBody& m) {
  j = {{field::kError, m.error}};
  if (!m.path.empty()) j[field::kPath] = m.path;
}

void from_json(const nlohmann::json& j, ErrorBody& m) {
  j.at(field::kError).get_to(m.error);
  m.path = j.value(field::kPath, "");
}

}  // namespace vesper::protocol
