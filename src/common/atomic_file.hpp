#pragma once
/// Write-then-rename: a result file is produced under a temporary name beside its final path
/// and renamed into place only when complete, so a failed run never replaces a good file.
#include <filesystem>

namespace roifem {

class AtomicFile {
 public:
  /// `suffix` is kept at the end of the temporary name (some writers pick the format by extension).
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

}  // namespace roifem
