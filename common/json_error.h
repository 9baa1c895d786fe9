#pragma once
// JsonError: a JSON document that is not what its reader expected. It names
// the document (usually its file), the JSON pointer of the offending value and
// what was wrong; what() reads "<file>: <json path>: <message>", e.g.
// "scene.json: /shapes/3/radius: expected a positive number, got -1", or
// "<file>: <message>" when there is no path (unreadable file, invalid JSON).
#include <stdexcept>
#include <string>

namespace vesper {

class JsonError : public std::runtime_error {
 public:
  JsonError(std::string file, std::string json_path, std::string message)
      : std::runtime_error(file + ": " + (json_path.empty() ? "" : json_path + ": ") + message),
        file_(std::move(file)),
        json_path_(std::move(json_path)),
        message_(std::move(message)) {}

  const std::string& file() const { return file_; }
  const std::string& json_path() const { return json_path_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_, json_path_, message_;
};

// Runs `read` and rethrows a JsonError as the format's own error type (a
// SuiteError, a BenchSetError: JsonErrors with the same three parts), so a
// caller can tell which kind of file was bad.
template <class Error, class Read>
auto rethrow_json_error_as(Read read) -> decltype(read()) {
  try {
    return read();
  } catch (const JsonError& e) {
    throw Error(e.file(), e.json_path(), e.message());
  }
}

}  // namespace vesper
