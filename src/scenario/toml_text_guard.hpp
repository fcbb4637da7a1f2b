// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <string_view>

namespace roifem::scenario {

/// Refuses a scenario text that would send toml++ 3.3 (Debian 12) into undefined behaviour, with
/// the file, line and column, before toml++ sees it.
///
/// toml++ 3.3 classifies characters as whitespace through a generated table that reaches
/// TOML_UNREACHABLE for most code points in U+00A1..U+0499 and U+2C5E..U+3057 (upstream issues
/// #190 and #295, fixed after 3.3). It classifies every character it scans outside a string: in
/// code, in the run of a bare value (`1."é"` is scanned to its end before it is refused), after a
/// backslash in a multi-line string and after the blanks a line-ending backslash trims. TOML 1.0
/// allows non-ASCII characters only inside strings and comments, so a non-ASCII character in any
/// of those places is refused; inside a string or comment it is fine. A quote opens a string only
/// where TOML lets a key or a value begin.
void check_toml_text(std::string_view text, const std::string& source);

}  // namespace roifem::scenario
