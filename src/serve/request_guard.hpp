// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Who may talk to `roifem serve`: the checks every request passes before it is served.
///  - The address to listen on must be an IP address (checked before any model is prepared).
///  - DNS rebinding: a page on another site can point its own name at 127.0.0.1 and reach the
///    server as "its" host; its requests then carry that name in Host. So Host must name the
///    loopback (localhost, 127.0.0.0/8, ::1) or the address the server listens on (any IP address
///    when it listens on all of them): an IP literal cannot be rebound. Plain HTTP is held to this
///    as the WebSocket is.
///  - A browser's WebSocket must come from the page's own origin: Origin = "http://" + Host.
#include <optional>
#include <string>
#include <string_view>

namespace roifem::serve {

/// InputError naming --host when `host` is not an IP address.
void check_listen_address(const std::string& host);
/// Whether `host` (an IP address) is a loopback address.
bool is_loopback_address(const std::string& host);
/// Whether a request's Host header (name or address, with or without ":port"; IPv6 in brackets)
/// names the loopback or `listen_host`; none (an HTTP/1.1 request without Host) is refused.
bool host_allowed(std::optional<std::string_view> host_header, const std::string& listen_host);
/// Whether a WebSocket upgrade's Origin is the page's own ("http://" + Host); a request without
/// Origin comes from no page (not a browser) and is allowed.
bool origin_allowed(std::optional<std::string_view> origin, std::optional<std::string_view> host_header);

}  // namespace roifem::serve
