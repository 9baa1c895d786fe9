#include "server/monitor_auth.h"

#include "common/sha256.h"

namespace vesper {

using protocol::Endpoint;
using protocol::Method;
using protocol::Role;

std::string session_value(const std::string& submitter_token) {
  // A label keeps the value apart from any other hash of the token.
  return sha256_hex("vesper monitor session v1\n" + submitter_token);
}

std::string session_cookie(const std::string& value) {
  // No Domain: the cookie goes back only to this host; no Max-Age: it ends
  // with the browser session. No Secure: the server speaks plain HTTP (put a
  // TLS proxy in front of a farm on a network, docs/farm.md).
  return std::string(protocol::kSessionCookie) + "=" + value +
         "; Path=/; HttpOnly; SameSite=Strict";
}

std::string expired_session_cookie() {
  return std::string(protocol::kSessionCookie) + "=; Path=/; HttpOnly; SameSite=Strict; Max-Age=0";
}

std::string cookie_value(std::string_view header, std::string_view name) {
  while (!header.empty()) {
    const size_t semi = header.find(';');
    std::string_view pair = header.substr(0, semi);
    header = semi == std::string_view::npos ? std::string_view() : header.substr(semi + 1);
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    const size_t eq = pair.find('=');
    if (eq != std::string_view::npos && pair.substr(0, eq) == name)
      return std::string(pair.substr(eq + 1));
  }
  return {};
}

bool cookie_may_authorize(const protocol::Route& r) {
  if (r.role != Role::Submitter && r.role != Role::Either) return false;
  // Reading, and acting on jobs (cancel, pause, resume, retry, delete); not
  // submitting work or storing bytes.
  return r.endpoint != Endpoint::SubmitJob && r.method != Method::Put;
}

bool read_only_viewable(const protocol::Route& r) {
  switch (r.endpoint) {
    case Endpoint::ListJobs:
    case Endpoint::GetJob:
    case Endpoint::TaskLog:
    case Endpoint::ListFrames:
    case Endpoint::ListWorkers:
    case Endpoint::FrameThumbnail:
    case Endpoint::FrameHistogram:
      return r.method == Method::Get;
    default:
      return false;
  }
}

}  // namespace vesper
