// The request guard of `intrinsic serve` (app/serve/request_guard.h) on
// header values, without sockets: which Host and Origin headers pass, the
// token's form and randomness, cookie parsing, and the order of the checks.
// test_serve_guard.cpp checks the same against the running server.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <set>

#include "../app/serve/request_guard.h"

namespace intrinsic::app {
namespace {

TEST(RequestGuard, ParsesAuthorities) {
  const auto a = parse_authority("LocalHost:8080", 80);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->name, "localhost");
  EXPECT_EQ(a->port, 8080);
  EXPECT_EQ(parse_authority("127.0.0.1", 80)->port, 80);
  EXPECT_EQ(parse_authority("[::1]:9", 80)->name, "[::1]");
  EXPECT_EQ(parse_authority("[::1]", 80)->port, 80);
  for (const char* bad : {"", ":80", "a:", "a:0", "a:65536", "a:+80", "a:8 0", "a b:80", "user@a:80", "a:80/x",
                          "[::1", "[::1]x", "[::1]:", "[a b]:1", "a:1:2", "::1"})
    EXPECT_FALSE(parse_authority(bad, 80)) << bad;
}

TEST(RequestGuard, HostsAreTheLoopbackNamesAndTheBoundAddressWithThePort) {
  const HostPolicy p = host_policy("127.0.0.1", 8123, {"192.168.1.7"});
  for (const char* good : {"127.0.0.1:8123", "localhost:8123", "LOCALHOST:8123", "[::1]:8123"})
    EXPECT_TRUE(host_allowed(p, good)) << good;
  // A foreign name (DNS rebinding), no Host, the wrong or the default port,
  // a machine address when bound to loopback only.
  for (const char* bad : {"evil.example:8123", "evil.example", "", "127.0.0.1:8124", "127.0.0.1", "localhost",
                          "192.168.1.7:8123", "127.0.0.1.evil.example:8123", "localhost.:8123"})
    EXPECT_FALSE(host_allowed(p, bad)) << bad;
  EXPECT_FALSE(host_allowed(p, "127.0.0.1:8123", 2)) << "two Host headers";
  EXPECT_FALSE(host_allowed(p, "127.0.0.1:8123", 0));
  // Port 80: a browser writes no port.
  EXPECT_TRUE(host_allowed(host_policy("127.0.0.1", 80, {}), "localhost"));
}

TEST(RequestGuard, AWildcardBindAlsoAcceptsTheMachinesAddresses) {
  const HostPolicy any = host_policy("0.0.0.0", 8000, {"192.168.1.7", "fe80::1", "MyBox"});
  for (const char* good : {"192.168.1.7:8000", "[fe80::1]:8000", "mybox:8000", "0.0.0.0:8000", "localhost:8000"})
    EXPECT_TRUE(host_allowed(any, good)) << good;
  EXPECT_FALSE(host_allowed(any, "evil.example:8000"));
  EXPECT_TRUE(is_wildcard_address("::"));
  EXPECT_FALSE(is_wildcard_address("127.0.0.1"));
  const HostPolicy v6 = host_policy("::1", 8000, {"192.168.1.7"});
  EXPECT_TRUE(host_allowed(v6, "[::1]:8000"));
  EXPECT_FALSE(host_allowed(v6, "192.168.1.7:8000"));
  // The real machine: at least the loopback interface, every name parses as a Host.
  const std::vector<std::string> mine = machine_addresses();
  EXPECT_NE(std::find(mine.begin(), mine.end(), "127.0.0.1"), mine.end());
  for (const std::string& n : mine) EXPECT_TRUE(parse_authority(n + ":1", 80)) << n;
}

TEST(RequestGuard, OriginMustBeTheRequestsOwn) {
  EXPECT_TRUE(origin_allowed("", "127.0.0.1:8123"));
  EXPECT_TRUE(origin_allowed("http://127.0.0.1:8123", "127.0.0.1:8123"));
  EXPECT_TRUE(origin_allowed("HTTP://LOCALHOST:8123", "localhost:8123"));
  EXPECT_TRUE(origin_allowed("http://localhost", "localhost:80"));
  for (const char* bad : {"http://evil.example", "http://evil.example:8123", "null", "https://127.0.0.1:8123",
                          "http://127.0.0.1:8124", "http://localhost:8123", "http://127.0.0.1:8123/", "file://"})
    EXPECT_FALSE(origin_allowed(bad, "127.0.0.1:8123")) << bad;
}

TEST(RequestGuard, BrowsersMustSaySameOrigin) {
  for (const char* good : {"", "same-origin", "none"}) EXPECT_TRUE(fetch_site_allowed(good)) << good;
  for (const char* bad : {"same-site", "cross-site", "other"}) EXPECT_FALSE(fetch_site_allowed(bad)) << bad;
  const HostPolicy p = host_policy("127.0.0.1", 8123, {});
  const std::string token = random_token();
  RequestFacts r{"GET", "/api/mesh", "127.0.0.1:8123"};
  r.token_header = token;
  r.fetch_site = "same-site";  // another server's page on 127.0.0.1: the cookie would go along
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::ForeignOrigin);
  r.fetch_site = "same-origin";
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::None);
}

TEST(RequestGuard, TokensAre128RandomBitsInHex) {
  std::set<std::string> seen;
  for (int k = 0; k < 200; ++k) {
    const std::string t = random_token();
    ASSERT_EQ(t.size(), 32u);
    for (const char c : t) ASSERT_TRUE(std::isdigit(static_cast<unsigned char>(c)) || (c >= 'a' && c <= 'f')) << t;
    seen.insert(t);
  }
  EXPECT_EQ(seen.size(), 200u);
  // Each hex digit position takes many values over the draws (no constant part).
  for (size_t i = 0; i < 32; ++i) {
    std::set<char> digits;
    for (const std::string& t : seen) digits.insert(t[i]);
    EXPECT_GE(digits.size(), 8u) << i;
  }
  const std::string t = random_token();
  EXPECT_TRUE(token_matches(t, t));
  EXPECT_FALSE(token_matches(t.substr(0, 31), t));
  EXPECT_FALSE(token_matches(t + "0", t));
  EXPECT_FALSE(token_matches("", t));
  EXPECT_FALSE(token_matches("", ""));
  std::string flipped = t;
  flipped[17] = flipped[17] == 'a' ? 'b' : 'a';
  EXPECT_FALSE(token_matches(flipped, t));
}

TEST(RequestGuard, CookieParsing) {
  EXPECT_EQ(cookie_value("a=1; intrinsic_token_8080=abc; b=2", "intrinsic_token_8080"), "abc");
  EXPECT_EQ(cookie_value("intrinsic_token_8080=abc", "intrinsic_token_8080"), "abc");
  EXPECT_EQ(cookie_value("x_intrinsic_token_8080=abc", "intrinsic_token_8080"), "");
  EXPECT_EQ(cookie_value("intrinsic_token_8081=abc", "intrinsic_token_8080"), "");
  EXPECT_EQ(cookie_value("", "intrinsic_token_8080"), "");
  EXPECT_EQ(cookie_value(";;  ; intrinsic_token_8080=q ;", "intrinsic_token_8080"), "q");
  const std::string c = token_cookie("abc", 8080);
  EXPECT_EQ(c.rfind("intrinsic_token_8080=abc;", 0), 0u) << c;
  EXPECT_NE(c.find("HttpOnly"), std::string::npos);
  EXPECT_NE(c.find("SameSite=Strict"), std::string::npos);
  EXPECT_NE(c.find("Path=/"), std::string::npos);
}

TEST(RequestGuard, ChecksInOrderAndWhereTheTokenMayBe) {
  const HostPolicy p = host_policy("127.0.0.1", 8123, {});
  const std::string token = random_token(), other = random_token();
  RequestFacts api{"GET", "/api/mesh", "127.0.0.1:8123"};
  EXPECT_EQ(check_request(p, token, api).refusal, Refusal::MissingToken);
  RequestFacts r = api;
  r.token_header = token;
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::None);
  EXPECT_FALSE(check_request(p, token, r).set_cookie);
  r.token_header = other;
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::WrongToken);
  r = api;
  r.cookie = "theme=dark; " + token_cookie_name(8123) + "=" + token;
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::None);
  r.cookie = token_cookie_name(8124) + "=" + token;  // another server's cookie
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::MissingToken);
  r = api;
  r.token_query = token;  // not for the API
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::MissingToken);
  // The page: ?token= sets the cookie; a stale cookie does not matter then.
  RequestFacts page{"GET", "/", "localhost:8123"};
  EXPECT_EQ(check_request(p, token, page).refusal, Refusal::MissingToken);
  page.token_query = token;
  page.cookie = token_cookie_name(8123) + "=" + other;
  const Verdict v = check_request(p, token, page);
  EXPECT_EQ(v.refusal, Refusal::None);
  EXPECT_TRUE(v.set_cookie);
  page.token_query = other;
  EXPECT_EQ(check_request(p, token, page).refusal, Refusal::WrongToken);
  // Host before Origin before the token.
  r = api;
  r.token_header = token;
  r.host = "evil.example:8123";
  r.origin = "http://evil.example:8123";
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::BadHost);
  r.host = "127.0.0.1:8123";
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::ForeignOrigin);
  r.origin = "http://127.0.0.1:8123";
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::None);
  // Bodies need a length (and only after the token: strangers learn nothing more).
  r.method = "POST";
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::LengthRequired);
  r.has_content_length = true;
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::None);
  r.has_transfer_encoding = true;
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::LengthRequired);
  r.token_header = "";
  EXPECT_EQ(check_request(p, token, r).refusal, Refusal::MissingToken);
  EXPECT_EQ(refusal_status(Refusal::BadHost), 400);
  EXPECT_EQ(refusal_status(Refusal::ForeignOrigin), 403);
  EXPECT_EQ(refusal_status(Refusal::MissingToken), 403);
  EXPECT_EQ(refusal_status(Refusal::WrongToken), 403);
  EXPECT_EQ(refusal_status(Refusal::LengthRequired), 411);
  EXPECT_NE(refusal_message(Refusal::BadHost).find("Host"), std::string::npos);
}

}  // namespace
}  // namespace intrinsic::app
