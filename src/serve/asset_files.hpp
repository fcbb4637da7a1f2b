// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The files the page is made of, and nothing else: a URL path names a file under one of a few
/// roots (the page's own folder, Debian's three.js), chosen by prefix. A path that leaves its root
/// (.., an encoded dot or slash, a link pointing out), names a folder or names no file resolves to
/// nothing, which the server answers with 404.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace roifem::serve {

struct AssetRoot {
  std::string prefix;               ///< URL prefix, "/" or "/three/"
  std::filesystem::path directory;  ///< what it serves
};

class AssetFiles {
 public:
  /// Roots tried longest prefix first. "/" maps to index.html in the "/" root.
  explicit AssetFiles(std::vector<AssetRoot> roots);
  /// The file a GET of `target` (path and query, as the request line has it) serves, or nothing.
  std::optional<std::filesystem::path> resolve(std::string_view target) const;
  /// The Content-Type for a file's name.
  static std::string_view content_type(const std::filesystem::path& file);

 private:
  std::vector<AssetRoot> roots_;
};

/// Where the page's files are: $ROIFEM_WEB_DIR, the source tree's web/ (a build) or the installed copy.
std::filesystem::path page_directory();
/// Debian's three.js (libjs-three): /usr/share/javascript/three.
std::filesystem::path three_directory();

}  // namespace roifem::serve
