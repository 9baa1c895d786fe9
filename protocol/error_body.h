#pragma once
// The body of every error answer: {"error": "what went wrong and what was
// expected", "path": "/json/pointer"}; `path` only when the error is about a
// value in the request body.
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace vesper::protocol {

struct ErrorBody {
  std::string error;
  std::string path;  // RFC 6901 pointer; empty: left out
};

void to_json(nlohmann::json& j, const ErrorBody& m);
void from_json(const nlohmann::json& j, ErrorBody& m);

}  // namespace vesper::protocol
