// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/csv.hpp"

#include <cstdarg>
#include <vector>

#include "common/errors.hpp"
#include "common/version.hpp"

namespace roifem::io {

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::string& header) : file_(path), out_(file_.temporary_path()) {
  if (!out_) throw InputError(path.string() + ": cannot create file");
  out_ << "# roifem " << version() << '\n' << header << '\n';
}

void CsvWriter::row(const std::string& line) { out_ << line << '\n'; }

void CsvWriter::close() {
  out_.flush();
  if (!out_) throw InputError(file_.final_path().string() + ": write failed (disk full?)");
  out_.close();
  file_.commit();
}

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

}  // namespace roifem::io
