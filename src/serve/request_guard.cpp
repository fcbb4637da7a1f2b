// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/request_guard.hpp"

#include <algorithm>
#include <boost/asio/ip/address.hpp>
#include <cctype>

#include "common/errors.hpp"

namespace roifem::serve {

namespace {

/// The name or address of a Host header, without its port and an IPv6 address's brackets.
std::string host_name(std::string_view header) {
  if (!header.empty() && header.front() == '[') {
    const auto close = header.find(']');
    return close == std::string_view::npos ? std::string() : std::string(header.substr(1, close - 1));
  }
  const auto colon = header.find(':');
  return std::string(header.substr(0, colon));
}

std::optional<boost::asio::ip::address> address_of(const std::string& text) {
  boost::system::error_code ec;
  const auto address = boost::asio::ip::make_address(text, ec);
  if (ec) return std::nullopt;
  return address;
}

}  // namespace

void check_listen_address(const std::string& host) {
  boost::system::error_code ec;
  boost::asio::ip::make_address(host, ec);
  if (ec) throw InputError("serve: --host '" + host + "' is not an IP address (" + ec.message() + ")");
}

bool is_loopback_address(const std::string& host) {
  const auto address = address_of(host);
  return address && address->is_loopback();
}

bool host_allowed(std::optional<std::string_view> host_header, const std::string& listen_host) {
  if (!host_header) return false;
  std::string name = host_name(*host_header);
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (name == "localhost") return true;
  const auto address = address_of(name);
  if (!address) return false;  // a name other than localhost: it could be rebound to us
  if (address->is_loopback()) return true;
  // Listening on every address (0.0.0.0, ::), any of the machine's addresses may be the one a
  // client reached: an IP literal, which no other site can rebind.
  const auto listening = address_of(listen_host);
  return listening && (listening->is_unspecified() || *address == *listening);
}

bool origin_allowed(std::optional<std::string_view> origin, std::optional<std::string_view> host_header) {
  if (!origin) return true;
  return host_header && *origin == "http://" + std::string(*host_header);
}

}  // namespace roifem::serve
