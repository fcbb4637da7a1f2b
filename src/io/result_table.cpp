// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/result_table.hpp"
#include "common/format.hpp"

#include <algorithm>

namespace roifem::io {

std::string csv_cell(const Cell& cell, const char* real_format, bool quoted) {
  struct Text {
    const char* real_format;
    bool quoted;
    std::string operator()(std::monostate) const { return ""; }
    std::string operator()(bool flag) const { return flag ? "1" : "0"; }
    std::string operator()(long n) const { return std::to_string(n); }
    std::string operator()(double x) const { return format(real_format, x); }
    std::string operator()(std::string text) const {
      if (!quoted) return text;
      std::replace(text.begin(), text.end(), '"', '\'');
      return "\"" + text + "\"";
    }
  };
  return std::visit(Text{real_format, quoted}, cell);
}

}  // namespace roifem::io
