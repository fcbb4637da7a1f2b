// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// printf-style formatting to std::string: what most messages and tables are made with.
#include <string>

namespace roifem {

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace roifem
