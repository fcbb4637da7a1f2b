// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/format.hpp"

#include <cstdarg>
#include <cstdio>
#include <vector>

namespace roifem {

std::string format(const char* fmt, ...) {
  va_list args, copy;
  va_start(args, fmt);
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, copy);
  va_end(copy);
  std::vector<char> buffer(static_cast<std::size_t>(n) + 1);
  std::vsnprintf(buffer.data(), buffer.size(), fmt, args);
  va_end(args);
  return std::string(buffer.data(), static_cast<std::size_t>(n));
}

}  // namespace roifem
