#pragma once
// Who may call a route from the browser monitor. The page logs in with the
// submitter token (POST /api/v1/login) and gets a session cookie (HttpOnly,
// SameSite=Strict, host-only, Path=/) whose value is derived from the token:
// the cookie is not the token, and replacing the token in tokens.json ends
// every session. The cookie stands in for the submitter token on GETs and on
// job actions, never on a submission or an upload; a state-changing request
// it authorises must also carry the X-Vesper-Monitor header, which a
// cross-site form cannot send. With `monitor_read_only` the monitor's GETs
// need no token at all (the frames' EXRs and the blobs still do).
#include <string>
#include <string_view>

#include "protocol/routes.h"

namespace vesper {

// The session cookie's value for a submitter token.
std::string session_value(const std::string& submitter_token);
// Set-Cookie values: a session, and one that ends it (logout).
std::string session_cookie(const std::string& value);
std::string expired_session_cookie();

// The value of cookie `name` in a Cookie header ("a=1; b=2"), or "".
std::string cookie_value(std::string_view header, std::string_view name);

// Whether the session cookie may stand in for the submitter token on `r`.
bool cookie_may_authorize(const protocol::Route& r);
// Whether `r` is readable without a token when the monitor is read-only.
bool read_only_viewable(const protocol::Route& r);

}  // namespace vesper
