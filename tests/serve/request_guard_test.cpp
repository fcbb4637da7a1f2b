// SPDX-License-Identifier: GPL-3.0-or-later
// Who may talk to roifem serve (serve/request_guard.hpp): Host names the loopback or the listening
// address, a WebSocket's Origin is the page's own, --host is an address.
#include "serve/request_guard.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace roifem::serve {
namespace {

TEST(RequestGuard, HostMustNameTheLoopbackOrTheListeningAddress) {
  for (const char* host : {"127.0.0.1", "127.0.0.1:8080", "127.1.2.3:80", "localhost", "LocalHost:8080", "[::1]:8080", "[::1]"})
    EXPECT_TRUE(host_allowed(host, "127.0.0.1")) << host;
  for (const char* host :
       {"evil.example", "evil.example:8080", "localhost.evil.example", "127.0.0.1.nip.io", "10.0.0.5:8080", "[::1", "", ":8080"})
    EXPECT_FALSE(host_allowed(host, "127.0.0.1")) << host;
  EXPECT_FALSE(host_allowed(std::nullopt, "127.0.0.1"));
  // Listening on one address: that address too; on every address: any IP literal, never a name.
  EXPECT_TRUE(host_allowed("192.168.1.5:8080", "192.168.1.5"));
  EXPECT_FALSE(host_allowed("192.168.1.6:8080", "192.168.1.5"));
  EXPECT_TRUE(host_allowed("192.168.1.6:8080", "0.0.0.0"));
  EXPECT_TRUE(host_allowed("[fe80::1]:8080", "::"));
  EXPECT_FALSE(host_allowed("evil.example:8080", "0.0.0.0"));
}

TEST(RequestGuard, AWebSocketComesFromThePagesOwnOrigin) {
  EXPECT_TRUE(origin_allowed("http://127.0.0.1:8080", "127.0.0.1:8080"));
  EXPECT_TRUE(origin_allowed(std::nullopt, "127.0.0.1:8080"));  // no page: not a browser
  EXPECT_FALSE(origin_allowed("http://evil.example", "127.0.0.1:8080"));
  EXPECT_FALSE(origin_allowed("https://127.0.0.1:8080", "127.0.0.1:8080"));
  EXPECT_FALSE(origin_allowed("http://127.0.0.1:8080", std::nullopt));
}

TEST(RequestGuard, TheListeningAddressMustBeAnIpAddress) {
  EXPECT_NO_THROW(check_listen_address("127.0.0.1"));
  EXPECT_NO_THROW(check_listen_address("::1"));
  EXPECT_THROW(check_listen_address("not-an-address"), InputError);
  EXPECT_THROW(check_listen_address("localhost"), InputError);
  EXPECT_TRUE(is_loopback_address("127.0.0.1"));
  EXPECT_TRUE(is_loopback_address("::1"));
  EXPECT_FALSE(is_loopback_address("0.0.0.0"));
}

}  // namespace
}  // namespace roifem::serve
