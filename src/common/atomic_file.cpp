// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <system_error>
#include <vector>

#include "common/errors.hpp"

namespace roifem {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path final_path) : final_(std::move(final_path)) {
  if (final_.has_parent_path()) ensure_writable_directory(final_.parent_path());
  // Same directory (rename is atomic only within a file system), same extension (Gmsh, HDF5
  // and XDMF readers look at it), a process id so two runs never share a temporary.
  temporary_ = final_;
  temporary_.replace_filename("." + final_.stem().string() + ".partial-" + std::to_string(::getpid()) +
                              final_.extension().string());
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ignored;
    fs::remove(temporary_, ignored);
  }
}

void AtomicFile::commit() { commit_as(final_); }

void AtomicFile::commit_as(const fs::path& path) {
  std::error_code ec;
  fs::rename(temporary_, path, ec);
  if (ec) throw InputError(path.string() + ": cannot move the finished file into place: " + ec.message());
  committed_ = true;
}

void ensure_writable_directory(const fs::path& directory) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) throw InputError(directory.string() + ": cannot create output directory: " + ec.message());
  if (::access(directory.c_str(), W_OK) != 0) throw InputError(directory.string() + ": output directory is not writable");
}

void check_output_directory(const fs::path& directory) {
  std::error_code ec;
  if (fs::exists(directory, ec) && !fs::is_directory(directory, ec))
    throw InputError(directory.string() + ": cannot create output directory: it is a file");
  // A missing directory is created as a probe (permissions alone do not tell: root may write
  // anywhere but /proc), then removed again, up to the nearest ancestor that existed.
  std::vector<fs::path> missing;
  for (fs::path p = fs::absolute(directory, ec); !p.empty() && !fs::exists(p, ec) && p != p.parent_path(); p = p.parent_path())
    missing.push_back(p);
  ensure_writable_directory(directory);
  for (const fs::path& p : missing) fs::remove(p, ec);
}

}  // namespace roifem
