// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Computed arrays kept on disk between runs, keyed by the text of everything they depend on (the
/// inputs, written out in full: exact numbers as hexadecimal floats, and roifem's version), so that
/// a second run with the same inputs reads what the first computed, bit for bit, in place of
/// minutes of work. A file per key, named by the key's hash, holding the key itself: a file whose
/// key differs (a hash collision, another version) is a miss. Written under a temporary name and
/// renamed when complete (common/atomic_file.hpp); a file that cannot be read is a miss, one that
/// cannot be written a warning, never an error: a cache is never needed.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace roifem::io {

class ResultCache {
 public:
  /// `directory` empty: no cache (every load misses, nothing is stored).
  explicit ResultCache(std::filesystem::path directory = {}) : directory_(std::move(directory)) {}
  bool enabled() const { return !directory_.empty(); }
  const std::filesystem::path& directory() const { return directory_; }
  std::optional<std::vector<double>> load(const std::string& key) const;
  /// Returns "" when stored, else why not (for a warning).
  std::string store(const std::string& key, const std::vector<double>& values) const;
  /// The file that holds `key`'s values.
  std::filesystem::path file_of(const std::string& key) const;

 private:
  std::filesystem::path directory_;
};

/// A double exactly, for a key: "0x1.999999999999ap-4".
std::string exact(double x);

/// The user's cache directory for roifem: $XDG_CACHE_HOME/roifem, else $HOME/.cache/roifem, else
/// none (empty).
std::filesystem::path default_cache_directory();

}  // namespace roifem::io
