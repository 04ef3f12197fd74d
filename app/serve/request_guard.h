// Who may talk to `intrinsic serve` (docs/cli.md "intrinsic serve"): the checks
// every request passes before any route runs, as trusted local servers
// (Jupyter, Vite) do. A web page the user visits can reach a loopback server:
// through DNS rebinding (its own name resolving to 127.0.0.1, so the Host
// header carries that name) or by plain cross-origin requests (a foreign
// Origin, and no way to know the per-launch token). Plain functions on header
// values, so they are tested without sockets (tests/test_request_guard.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace intrinsic::app {

// A Host header or an Origin's authority: name in lower case (an IPv6
// address keeps its brackets, as Host headers write it) and port.
struct Authority {
  std::string name;
  int port = 0;
};

// "name", "name:port", "[v6]", "[v6]:port"; `default_port` when no port is
// written. nullopt for anything else (empty, user info, paths, bad ports).
std::optional<Authority> parse_authority(const std::string& text, int default_port);

// 0.0.0.0 or :: (every interface).
bool is_wildcard_address(const std::string& bound);

// The names a Host header may carry, with the bound port: localhost,
// 127.0.0.1, [::1], the bound address and, for a wildcard bind,
// `machine_names` (machine_addresses()).
struct HostPolicy {
  std::vector<std::string> names;
  int port = 0;
};
HostPolicy host_policy(const std::string& bound, int port, const std::vector<std::string>& machine_names);

// This machine's interface addresses (IPv6 in brackets) and host name, lower case.
std::vector<std::string> machine_addresses();

// `count`: how many Host headers the request has (exactly one is allowed).
bool host_allowed(const HostPolicy& policy, const std::string& host_header, size_t count = 1);

// No Origin header (empty), or exactly the request's own origin
// http://HOST (compared as authorities, so the default port 80 may be
// written or not). "null" and other schemes are foreign.
bool origin_allowed(const std::string& origin_header, const std::string& host_header);

// Sec-Fetch-Site absent (not a browser), "same-origin" or "none" (the user
// opened the URL). Browsers send no Origin with a plain GET from an <img>
// or <script> tag, and cookies are shared by every port of 127.0.0.1
// (another local server's page is "same-site"): this header still tells.
bool fetch_site_allowed(const std::string& sec_fetch_site);

// 128 bits from std::random_device as 32 lower-case hex digits.
std::string random_token();

// Compares in time independent of where they first differ.
bool token_matches(const std::string& given, const std::string& token);

// The value of cookie `name` in a Cookie header ("a=1; b=2"), "" when absent.
std::string cookie_value(const std::string& cookie_header, const std::string& name);

// The token's cookie name holds the port: cookies are shared by every port
// of a host, so two servers on one machine would otherwise overwrite each
// other's cookie in the same browser.
std::string token_cookie_name(int port);
// The Set-Cookie value: HttpOnly (no script reads it), SameSite=Strict (no
// other site's request carries it), for the whole server (Path=/).
std::string token_cookie(const std::string& token, int port);

// The header carrying the token for scripts (the page sends the cookie).
inline const char* const kTokenHeader = "X-Intrinsic-Token";

// What a request shows the guard. `token_query`: the `token` query parameter.
struct RequestFacts {
  std::string method, path;
  std::string host;
  size_t host_count = 1;
  std::string origin, cookie, token_header, token_query;
  std::string fetch_site;  // Sec-Fetch-Site (browsers send it), "" when absent
  bool has_content_length = false;
  bool has_transfer_encoding = false;
};

enum class Refusal { None, BadHost, ForeignOrigin, MissingToken, WrongToken, LengthRequired };

struct Verdict {
  Refusal refusal = Refusal::None;
  bool set_cookie = false;  // a page load with the right ?token=: give the browser the cookie
};

// In this order: Host (DNS rebinding), Origin and Sec-Fetch-Site (other
// sites' pages), token
// (/api/*: cookie or header; other paths also ?token=), then a request that
// carries a body must give its Content-Length and no Transfer-Encoding
// (cpp-httplib reads such bodies whole without the --max-body limit).
// The token cookie's name has policy.port.
Verdict check_request(const HostPolicy& policy, const std::string& token, const RequestFacts& r);

int refusal_status(Refusal r);           // 400, 403 or 411
std::string refusal_message(Refusal r);  // one line, plain text

}  // namespace intrinsic::app
