// The browser monitor's page and assets (embedded at build time from
// server/monitor/ by embed_assets.cmake), and its login.
#include <nlohmann/json.hpp>

#include "common/secret_token.h"
#include "common/utf8.h"
#include "server/api_error.h"
#include "server/handlers.h"
#include "server/monitor_assets.h"
#include "server/monitor_auth.h"
#include "server/tokens.h"

namespace vesper {
namespace {

using protocol::Endpoint;

// Everything the page loads comes from this server: no inline script, no
// other origin (a script injected into a job name could not run).
constexpr const char* kPolicy =
    "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; "
    "connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'self'";

ApiResponse asset(std::string_view name) {
  for (const EmbeddedAsset& a : kMonitorAssets)
    if (a.name == name) {
      ApiResponse r = text_response(std::string(a.body), std::string(a.content_type));
      r.headers.emplace_back("Content-Security-Policy", kPolicy);
      r.headers.emplace_back("X-Content-Type-Options", "nosniff");
      // Served from the binary: a new build may change them.
      r.headers.emplace_back("Cache-Control", "no-cache");
      return r;
    }
  throw ApiError(404, "the monitor has no file '" + utf8_safe(std::string(name), 80) + "'");
}

// {"token": "<submitter token>"} -> the session cookie; a wrong token is a 401.
ApiResponse login(TokenFile& tokens, const ApiRequest& req) {
  const nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
  if (!body.is_object() || !body.contains("token") || !body["token"].is_string())
    throw ApiError(400, "login: expected a JSON body {\"token\": \"<the submitter token>\"}",
                   "/token");
  const std::string token = body["token"].get<std::string>();
  const std::string submitter = tokens.current()->submitter;
  if (!constant_time_equal(token, submitter))
    throw ApiError(401,
                   "wrong token: the monitor takes the submitter token (\"submitter\" in "
                   "tokens.json in the server's data dir)",
                   "/token");
  ApiResponse r = json_response(200, {{"logged_in", true}});
  r.headers.emplace_back("Set-Cookie", session_cookie(session_value(submitter)));
  r.headers.emplace_back("Cache-Control", "no-store");
  return r;
}

ApiResponse logout() {
  ApiResponse r = json_response(200, {{"logged_in", false}});
  r.headers.emplace_back("Set-Cookie", expired_session_cookie());
  return r;
}

}  // namespace

void add_monitor_handlers(HandlerTable& table, TokenFile& tokens) {
  table[Endpoint::MonitorPage] = [](const ApiRequest&) { return asset("index.html"); };
  table[Endpoint::MonitorAsset] = [](const ApiRequest& r) { return asset(r.params.at(0)); };
  table[Endpoint::Login] = [&tokens](const ApiRequest& r) { return login(tokens, r); };
  table[Endpoint::Logout] = [](const ApiRequest&) { return logout(); };
}

}  // namespace vesper
