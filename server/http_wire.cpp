#include "server/http_wire.h"

#include <algorithm>
#include <cctype>

namespace vesper {
namespace {

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

// RFC 9110 token characters (method, field names).
bool is_token(std::string_view s) {
  if (s.empty()) return false;
  for (unsigned char c : s)
    if (!(std::isalnum(c) ||
          std::string_view("!#$%&'*+-.^_`|~").find(char(c)) != std::string_view::npos))
      return false;
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

void parse_query(std::string_view q, std::multimap<std::string, std::string>& out) {
  while (!q.empty()) {
    const size_t amp = q.find('&');
    const std::string_view pair = q.substr(0, amp);
    q = amp == std::string_view::npos ? std::string_view() : q.substr(amp + 1);
    if (pair.empty()) continue;
    const size_t eq = pair.find('=');
    out.emplace(
        percent_decode(pair.substr(0, eq), true),
        eq == std::string_view::npos ? std::string() : percent_decode(pair.substr(eq + 1), true));
  }
}

ParsedHead fail(std::string message) { return {std::nullopt, std::move(message)}; }

}  // namespace

std::string RequestHead::field(std::string_view name) const {
  for (const auto& [k, v] : fields)
    if (iequals(k, name)) return v;
  return {};
}

std::size_t RequestHead::field_count(std::string_view name) const {
  return size_t(std::count_if(fields.begin(), fields.end(),
                              [&](const auto& f) { return iequals(f.first, name); }));
}

bool RequestHead::wants_close() const {
  const std::string c = field("Connection");
  if (iequals(c, "close")) return true;
  return minor_version == 0 && !iequals(c, "keep-alive");
}

std::string percent_decode(std::string_view s, bool plus_is_space) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hex_digit(s[i + 1]) >= 0 && hex_digit(s[i + 2]) >= 0) {
      out += char(hex_digit(s[i + 1]) * 16 + hex_digit(s[i + 2]));
      i += 2;
    } else {
      out += plus_is_space && s[i] == '+' ? ' ' : s[i];
    }
  }
  return out;
}

ParsedHead parse_request_head(std::string_view bytes) {
  RequestHead h;
  size_t eol = bytes.find("\r\n");
  const std::string_view line = bytes.substr(0, eol);
  // Request line: METHOD SP target SP HTTP/1.x
  const size_t sp1 = line.find(' ');
  const size_t sp2 = sp1 == std::string_view::npos ? sp1 : line.find(' ', sp1 + 1);
  if (sp2 == std::string_view::npos || line.find(' ', sp2 + 1) != std::string_view::npos)
    return fail("malformed request line");
  h.method = std::string(line.substr(0, sp1));
  h.target = std::string(line.substr(sp1 + 1, sp2 - sp1 - 1));
  const std::string_view version = line.substr(sp2 + 1);
  if (!is_token(h.method)) return fail("malformed method");
  if (version == "HTTP/1.1")
    h.minor_version = 1;
  else if (version == "HTTP/1.0")
    h.minor_version = 0;
  else
    return fail("unsupported HTTP version (HTTP/1.0 or HTTP/1.1 expected)");
  if (h.target.empty() || h.target[0] != '/') return fail("request target is not an absolute path");
  const size_t qmark = h.target.find('?');
  h.path = percent_decode(std::string_view(h.target).substr(0, qmark), false);
  if (qmark != std::string::npos)
    parse_query(std::string_view(h.target).substr(qmark + 1), h.query);

  // Header fields, one per CRLF-terminated line; obsolete line folding and
  // bare CR/LF are refused rather than guessed at.
  while (eol != std::string_view::npos) {
    const size_t start = eol + 2;
    eol = bytes.find("\r\n", start);
    const std::string_view f =
        bytes.substr(start, eol == std::string_view::npos ? eol : eol - start);
    if (f.empty()) continue;
    if (f.find_first_of("\r\n") != std::string_view::npos || f[0] == ' ' || f[0] == '\t')
      return fail("malformed header line");
    const size_t colon = f.find(':');
    if (colon == std::string_view::npos || !is_token(f.substr(0, colon)))
      return fail("malformed header line");
    h.fields.emplace_back(std::string(f.substr(0, colon)), std::string(trim(f.substr(colon + 1))));
  }

  const size_t lengths = h.field_count("Content-Length");
  const bool transfer_encoding = h.field_count("Transfer-Encoding") > 0;
  if (lengths > 1) return fail("more than one Content-Length header");
  if (lengths == 1 && transfer_encoding)
    return fail("both Content-Length and Transfer-Encoding headers");
  if (lengths == 1) {
    const std::string v = h.field("Content-Length");
    if (v.empty() || v.size() > 19 ||
        !std::all_of(v.begin(), v.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return fail("malformed Content-Length");
    h.content_length = std::stoull(v);
    h.has_content_length = true;
  }
  h.chunked = transfer_encoding;
  return {std::move(h), {}};
}

std::string_view reason_phrase(int status) {
  switch (status) {
    case 100:
      return "Continue";
    case 200:
      return "OK";
    case 201:
      return "Created";
    case 204:
      return "No Content";
    case 400:
      return "Bad Request";
    case 401:
      return "Unauthorized";
    case 403:
      return "Forbidden";
    case 404:
      return "Not Found";
    case 408:
      return "Request Timeout";
    case 409:
      return "Conflict";
    case 411:
      return "Length Required";
    case 413:
      return "Payload Too Large";
    case 415:
      return "Unsupported Media Type";
    case 422:
      return "Unprocessable Content";
    case 431:
      return "Request Header Fields Too Large";
    case 500:
      return "Internal Server Error";
    case 503:
      return "Service Unavailable";
    default:
      return status < 300 ? "OK" : status < 500 ? "Client Error" : "Server Error";
  }
}

std::string response_head(int status,
                          const std::vector<std::pair<std::string, std::string>>& fields) {
  std::string out = "HTTP/1.1 " + std::to_string(status) + " ";
  out += reason_phrase(status);
  out += "\r\n";
  for (const auto& [k, v] : fields) {
    out += k;
    out += ": ";
    out += v;
    out += "\r\n";
  }
  out += "\r\n";
  return out;
}

}  // namespace vesper
