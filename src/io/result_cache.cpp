// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/result_cache.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "common/atomic_file.hpp"
#include "common/version.hpp"

namespace roifem::io {

namespace {

constexpr const char* magic = "roifem result cache 1\n";

/// FNV-1a, 64 bits: a file name for the key, not a check (the key itself is).
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

/// The key as stored: roifem's version first, so that another version's files miss.
std::string versioned(const std::string& key) { return "roifem " + std::string(version()) + "\n" + key; }

}  // namespace

std::string exact(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", x);
  return buffer;
}

std::filesystem::path ResultCache::file_of(const std::string& key) const {
  char name[40];
  std::snprintf(name, sizeof name, "%016llx.bin", static_cast<unsigned long long>(fnv1a(versioned(key))));
  return directory_ / name;
}

std::optional<std::vector<double>> ResultCache::load(const std::string& key) const {
  if (!enabled()) return std::nullopt;
  std::ifstream in(file_of(key), std::ios::binary);
  if (!in) return std::nullopt;
  const std::string text = versioned(key);
  std::string header(std::char_traits<char>::length(magic), '\0');
  std::uint64_t key_bytes = 0, count = 0;
  in.read(header.data(), static_cast<std::streamsize>(header.size()));
  in.read(reinterpret_cast<char*>(&key_bytes), sizeof key_bytes);
  if (!in || header != magic || key_bytes != text.size()) return std::nullopt;
  std::string stored(key_bytes, '\0');
  in.read(stored.data(), static_cast<std::streamsize>(key_bytes));
  in.read(reinterpret_cast<char*>(&count), sizeof count);
  if (!in || stored != text || count > (1ull << 32)) return std::nullopt;
  std::vector<double> values(count);
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(count * sizeof(double)));
  if (!in || in.peek() != std::char_traits<char>::eof()) return std::nullopt;
  return values;
}

std::string ResultCache::store(const std::string& key, const std::vector<double>& values) const {
  if (!enabled()) return "";
  try {
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec) return directory_.string() + ": " + ec.message();
    AtomicFile file(file_of(key));
    {
      std::ofstream out(file.temporary_path(), std::ios::binary);
      const std::string text = versioned(key);
      const std::uint64_t key_bytes = text.size(), count = values.size();
      out.write(magic, static_cast<std::streamsize>(std::char_traits<char>::length(magic)));
      out.write(reinterpret_cast<const char*>(&key_bytes), sizeof key_bytes);
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      out.write(reinterpret_cast<const char*>(&count), sizeof count);
      out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(count * sizeof(double)));
      out.flush();
      if (!out) return file.final_path().string() + ": write failed (disk full?)";
    }
    file.commit();
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::filesystem::path default_cache_directory() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0')
    return std::filesystem::path(xdg) / "roifem";
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
    return std::filesystem::path(home) / ".cache" / "roifem";
  return {};
}

}  // namespace roifem::io
