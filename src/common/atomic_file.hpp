// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Write-then-rename: a result file is produced under a temporary name beside its final path
/// and renamed into place only when complete, so a failed run never replaces a good file.
#include <filesystem>

namespace roifem {

class AtomicFile {
 public:
  /// Creates the final path's directory if it is missing (InputError if it cannot). The
  /// temporary name keeps the final extension (some writers pick the format by it).
  explicit AtomicFile(std::filesystem::path final_path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Removes the temporary file unless commit() succeeded.
  ~AtomicFile();

  const std::filesystem::path& temporary_path() const { return temporary_; }
  const std::filesystem::path& final_path() const { return final_; }
  /// Renames the temporary file to the final path (throws InputError on failure).
  void commit();
  /// Renames it to another path instead (an incomplete result, kept beside a good one).
  void commit_as(const std::filesystem::path& path);

 private:
  std::filesystem::path final_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

/// Throws InputError naming `directory` if it cannot be created or written.
void ensure_writable_directory(const std::filesystem::path& directory);

/// Fails early and leaves nothing behind: throws InputError naming `directory` unless it is a
/// writable directory or could be created (it is created and removed again to find out).
/// Commands call it before any work; the directory itself appears with the first AtomicFile, so
/// a run refused on its input leaves no empty directory behind.
void check_output_directory(const std::filesystem::path& directory);

}  // namespace roifem
