// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A CSV table written atomically (temporary name, renamed on close()).
#include <filesystem>
#include <fstream>
#include <string>

#include "common/atomic_file.hpp"

namespace roifem::io {

class CsvWriter {
 public:
  /// Its first line is "# roifem VERSION" (readers skip lines that start with #), then `header`.
  CsvWriter(const std::filesystem::path& path, const std::string& header);
  /// Appends one line (no newline needed).
  void row(const std::string& line);
  /// Flushes and moves the file into place; throws InputError naming the file on a write error.
  void close();

 private:
  AtomicFile file_;
  std::ofstream out_;
};

}  // namespace roifem::io
