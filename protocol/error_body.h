#pragma once
// The body of every error answer: {"error": "what went wrong and what was
// expected", "path": "/json/pointer"}; `path` only when the error is about a
// value in the request body.
#include <string>

#include "protocol/json_conversions.h"

namespace vesper::protocol {

struct ErrorBody {
  std::string error;
  std::string path;  // RFC 6901 pointer; empty: left out
};

VESPER_JSON_CONVERSIONS(ErrorBody);

}  // namespace vesper::protocol
