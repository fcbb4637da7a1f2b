// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Numbers in messages: the shortest form that keeps 9 significant digits ("1.70977e-10", "0.05"),
/// where std::to_string's fixed six decimals would print a small time as "0.000000".
#include <cstdio>
#include <string>

namespace roifem {

inline std::string number_text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  return buffer;
}

}  // namespace roifem
