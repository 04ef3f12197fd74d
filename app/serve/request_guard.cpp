// The request checks of `intrinsic serve` (request_guard.h).
#include "request_guard.h"  // by its directory: the tests build this file without app/ on the path

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <random>

namespace intrinsic::app {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// 1..65535 written with digits only (no sign, no spaces).
std::optional<int> parse_port(const std::string& s) {
  if (s.empty() || s.size() > 5) return std::nullopt;
  int port = 0;
  for (const char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    port = 10 * port + (c - '0');
  }
  if (port < 1 || port > 65535) return std::nullopt;
  return port;
}

bool all_of(const std::string& s, const char* extra) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [extra](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::string(extra).find(c) != std::string::npos;
  });
}

// An IPv6 address in brackets, as URLs and Host headers write it.
std::string bracketed(const std::string& address) {
  if (address.find(':') == std::string::npos || address.front() == '[') return address;
  return "[" + address + "]";
}

bool takes_body(const std::string& method) {
  return method == "POST" || method == "PUT" || method == "PATCH" || method == "DELETE" || method == "PRI";
}

}  // namespace

std::optional<Authority> parse_authority(const std::string& text, int default_port) {
  std::string name, port;
  if (!text.empty() && text.front() == '[') {
    const size_t close = text.find(']');
    if (close == std::string::npos) return std::nullopt;
    name = text.substr(0, close + 1);
    if (!all_of(name.substr(1, name.size() - 2), ":.")) return std::nullopt;
    const std::string rest = text.substr(close + 1);
    if (!rest.empty() && (rest.front() != ':' || (port = rest.substr(1)).empty())) return std::nullopt;
  } else {
    const size_t colon = text.find(':');
    name = text.substr(0, colon);
    if (colon != std::string::npos && (port = text.substr(colon + 1)).empty()) return std::nullopt;
    if (!all_of(name, "-.")) return std::nullopt;
  }
  Authority a{lower(name), default_port};
  if (!port.empty()) {
    const std::optional<int> p = parse_port(port);
    if (!p) return std::nullopt;
    a.port = *p;
  }
  return a;
}

bool is_wildcard_address(const std::string& bound) {
  return bound == "0.0.0.0" || bound == "::" || bound == "[::]";
}

HostPolicy host_policy(const std::string& bound, int port, const std::vector<std::string>& machine_names) {
  HostPolicy p;
  p.port = port;
  p.names = {"localhost", "127.0.0.1", "[::1]", lower(bracketed(bound))};
  if (is_wildcard_address(bound))
    for (const std::string& n : machine_names) p.names.push_back(lower(bracketed(n)));
  return p;
}

std::vector<std::string> machine_addresses() {
  std::vector<std::string> names;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) == 0) {
    for (const ifaddrs* i = list; i; i = i->ifa_next) {
      if (!i->ifa_addr) continue;
      char text[INET6_ADDRSTRLEN] = {};
      const int family = i->ifa_addr->sa_family;
      if (family == AF_INET) {
        inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr, text, sizeof text);
        names.push_back(text);
      } else if (family == AF_INET6) {
        inet_ntop(AF_INET6, &reinterpret_cast<const sockaddr_in6*>(i->ifa_addr)->sin6_addr, text, sizeof text);
        names.push_back("[" + std::string(text) + "]");
      }
    }
    freeifaddrs(list);
  }
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) == 0 && host[0]) names.push_back(lower(host));
  return names;
}

bool host_allowed(const HostPolicy& policy, const std::string& host_header, size_t count) {
  if (count != 1) return false;
  const std::optional<Authority> a = parse_authority(host_header, 80);
  if (!a || a->port != policy.port) return false;
  return std::find(policy.names.begin(), policy.names.end(), a->name) != policy.names.end();
}

bool origin_allowed(const std::string& origin_header, const std::string& host_header) {
  if (origin_header.empty()) return true;
  const std::string scheme = "http://";
  if (lower(origin_header.substr(0, scheme.size())) != scheme) return false;
  const std::optional<Authority> origin = parse_authority(origin_header.substr(scheme.size()), 80);
  const std::optional<Authority> host = parse_authority(host_header, 80);
  return origin && host && origin->name == host->name && origin->port == host->port;
}

bool fetch_site_allowed(const std::string& sec_fetch_site) {
  return sec_fetch_site.empty() || sec_fetch_site == "same-origin" || sec_fetch_site == "none";
}

std::string random_token() {
  std::random_device device;
  std::string token;
  for (int k = 0; k < 4; ++k) {
    char part[9];
    std::snprintf(part, sizeof part, "%08x", static_cast<unsigned>(device() & 0xffffffffu));
    token += part;
  }
  return token;
}

bool token_matches(const std::string& given, const std::string& token) {
  if (token.empty() || given.size() != token.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < token.size(); ++i) diff |= static_cast<unsigned char>(given[i] ^ token[i]);
  return diff == 0;
}

std::string cookie_value(const std::string& cookie_header, const std::string& name) {
  size_t at = 0;
  while (at < cookie_header.size()) {
    size_t end = cookie_header.find(';', at);
    if (end == std::string::npos) end = cookie_header.size();
    std::string pair = cookie_header.substr(at, end - at);
    const size_t first = pair.find_first_not_of(' ');
    pair = first == std::string::npos ? "" : pair.substr(first);
    const size_t eq = pair.find('=');
    if (eq != std::string::npos && pair.substr(0, eq) == name) {
      std::string value = pair.substr(eq + 1);
      while (!value.empty() && value.back() == ' ') value.pop_back();
      return value;
    }
    at = end + 1;
  }
  return "";
}

std::string token_cookie_name(int port) { return "intrinsic_token_" + std::to_string(port); }

std::string token_cookie(const std::string& token, int port) {
  return token_cookie_name(port) + "=" + token + "; Path=/; HttpOnly; SameSite=Strict";
}

Verdict check_request(const HostPolicy& policy, const std::string& token, const RequestFacts& r) {
  if (!host_allowed(policy, r.host, r.host_count)) return {Refusal::BadHost};
  if (!origin_allowed(r.origin, r.host) || !fetch_site_allowed(r.fetch_site)) return {Refusal::ForeignOrigin};
  // The API takes the token from the cookie or the header only: a token in
  // an API URL would end up in logs and histories for nothing.
  const bool api = r.path == "/api" || r.path.rfind("/api/", 0) == 0;
  const std::string cookie = cookie_value(r.cookie, token_cookie_name(policy.port));
  const std::string query = api ? "" : r.token_query;
  const bool by_query = token_matches(query, token);
  if (!by_query && !token_matches(r.token_header, token) && !token_matches(cookie, token)) {
    const bool none = query.empty() && r.token_header.empty() && cookie.empty();
    return {none ? Refusal::MissingToken : Refusal::WrongToken};
  }
  if (r.has_transfer_encoding || (takes_body(r.method) && !r.has_content_length)) return {Refusal::LengthRequired};
  return {Refusal::None, by_query};
}

int refusal_status(Refusal r) {
  switch (r) {
    case Refusal::None: return 200;
    case Refusal::BadHost: return 400;
    case Refusal::LengthRequired: return 411;
    default: return 403;
  }
}

std::string refusal_message(Refusal r) {
  switch (r) {
    case Refusal::None: return "";
    case Refusal::BadHost:
      return "bad Host header: this server answers to localhost, 127.0.0.1, [::1] or its bound address, with its port";
    case Refusal::ForeignOrigin: return "cross-origin request refused: it comes from another site's page";
    case Refusal::MissingToken:
      return "missing token: open the URL `intrinsic serve` printed (with ?token=), or send the X-Intrinsic-Token header";
    case Refusal::WrongToken: return "wrong token: open the URL `intrinsic serve` printed at its latest start";
    case Refusal::LengthRequired: return "a request body needs a Content-Length header (no Transfer-Encoding)";
  }
  return "";
}

}  // namespace intrinsic::app
