#pragma once
// HTTP/1.1 on the wire, as the server's connection layer needs it: a request
// head (request line + header fields) parsed from bytes, and a response head
// written as bytes. No I/O here (http_connections.* reads and writes).
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vesper {

struct RequestHead {
  std::string method;                             // "GET", ... (case-sensitive, as RFC 9110 says)
  std::string target;                             // as sent: "/api/v1/jobs?dry_run=1"
  std::string path;                               // the target's path, percent-decoded
  std::multimap<std::string, std::string> query;  // decoded ?key=value pairs
  int minor_version = 1;                          // HTTP/1.<minor>
  std::vector<std::pair<std::string, std::string>> fields;  // names as sent
  // Framing, decided by parse_request_head: the body's length (0 without
  // Content-Length) and whether the request said how long its body is.
  std::uint64_t content_length = 0;
  bool has_content_length = false;
  bool chunked = false;  // Transfer-Encoding present (no Content-Length)

  // The first value of field `name` (case-insensitive), or "".
  std::string field(std::string_view name) const;
  std::size_t field_count(std::string_view name) const;
  // Whether the connection should be closed after this request's answer
  // (`Connection: close`, or HTTP/1.0 without `Connection: keep-alive`).
  bool wants_close() const;
};

// The head's bytes, without the final empty line: an error message when they
// are not a request head we accept (the answer is 400 and the connection is
// closed). Ambiguous body lengths are errors too: two Content-Length fields,
// or one beside Transfer-Encoding (how requests are smuggled past a proxy).
struct ParsedHead {
  std::optional<RequestHead> head;
  std::string error;
};
ParsedHead parse_request_head(std::string_view bytes);

// "%2F" -> "/"; with `plus_is_space`, '+' -> ' ' (query strings). An invalid
// escape is kept as it is.
std::string percent_decode(std::string_view s, bool plus_is_space);

// "HTTP/1.1 <status> <reason>\r\n" + fields + "\r\n".
std::string response_head(int status,
                          const std::vector<std::pair<std::string, std::string>>& fields);
std::string_view reason_phrase(int status);

}  // namespace vesper
