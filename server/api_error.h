#pragma once
// An API error: HTTP status, a message, and the JSON path (RFC 6901 pointer,
// e.g. "/frames") of the offending value when the error is about the body.
#include <stdexcept>
#include <string>

namespace vesper {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message, std::string path = {})
      : std::runtime_error(message), status_(status), path_(std::move(path)) {}
  int status() const { return status_; }
  const std::string& path() const { return path_; }

 private:
  int status_;
  std::string path_;
};

}  // namespace vesper
