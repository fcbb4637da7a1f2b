// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/asset_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <system_error>

namespace roifem::serve {

namespace fs = std::filesystem;

namespace {

/// Only the characters a file name of ours uses: letters, digits, '-', '_', '.', '/'. Everything
/// else (a '%' escape, a backslash, a NUL) fails, so no decoding can turn a name into another.
bool plain(std::string_view path) {
  return std::all_of(path.begin(), path.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.' ||
           c == '/';
  });
}

/// No empty, "." or ".." segment, and no segment starting with a dot (hidden files).
bool segments_are_names(std::string_view path) {
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    const std::string_view segment = path.substr(start, end - start);
    if (segment.empty() || segment.front() == '.') return false;
    start = end + 1;
  }
  return true;
}

bool is_within(const fs::path& file, const fs::path& directory) {
  const auto [d, f] = std::mismatch(directory.begin(), directory.end(), file.begin(), file.end());
  return d == directory.end();
}

}  // namespace

AssetFiles::AssetFiles(std::vector<AssetRoot> roots) : roots_(std::move(roots)) {
  std::sort(roots_.begin(), roots_.end(),
            [](const AssetRoot& a, const AssetRoot& b) { return a.prefix.size() > b.prefix.size(); });
}

std::optional<fs::path> AssetFiles::resolve(std::string_view target) const {
  target = target.substr(0, target.find_first_of("?#"));
  if (target == "/") target = "/index.html";
  if (!plain(target)) return std::nullopt;
  for (const AssetRoot& root : roots_) {
    if (!target.starts_with(root.prefix)) continue;
    const std::string_view relative = target.substr(root.prefix.size());
    if (!segments_are_names(relative)) return std::nullopt;
    std::error_code error;
    const fs::path directory = fs::canonical(root.directory, error);
    if (error) return std::nullopt;
    const fs::path file = fs::canonical(directory / relative, error);  // links resolved: must stay inside
    if (error || !is_within(file, directory) || !fs::is_regular_file(file, error)) return std::nullopt;
    return file;
  }
  return std::nullopt;
}

std::string_view AssetFiles::content_type(const fs::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".png") return "image/png";
  if (extension == ".json") return "application/json";
  return "application/octet-stream";
}

fs::path page_directory() {
  if (const char* dir = std::getenv("ROIFEM_WEB_DIR"); dir != nullptr && *dir != '\0') return dir;
  if (fs::is_directory(ROIFEM_SOURCE_WEB_DIR)) return ROIFEM_SOURCE_WEB_DIR;
  return ROIFEM_INSTALLED_WEB_DIR;
}

fs::path three_directory() { return "/usr/share/javascript/three"; }

}  // namespace roifem::serve
