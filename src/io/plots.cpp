// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/plots.hpp"

#include <cstdlib>
#include <ostream>
#include <vector>

namespace roifem::io {

namespace fs = std::filesystem;

namespace {
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

bool run_plot_script(const std::string& script, const fs::path& directory, std::ostream& log,
                     const std::vector<std::string>& arguments) {
  std::vector<fs::path> candidates;
  if (const char* dir = std::getenv("ROIFEM_PLOT_DIR")) candidates.emplace_back(dir);
  candidates.emplace_back(ROIFEM_SOURCE_PLOT_DIR);
  candidates.emplace_back(ROIFEM_INSTALLED_PLOT_DIR);
  fs::path found;
  for (const auto& dir : candidates)
    if (fs::exists(dir / script)) {
      found = dir / script;
      break;
    }
  if (found.empty()) {
    log << "warning: plot script " << script << " not found; plots not drawn\n";
    return false;
  }
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  std::string command = python + " " + quoted(found.string()) + " " + quoted(directory.string());
  for (const std::string& a : arguments) command += " " + quoted(a);
  if (std::system(command.c_str()) != 0) {
    log << "warning: '" << command << "' failed (python3-matplotlib and python3-h5py installed?); plots not drawn\n";
    return false;
  }
  return true;
}

}  // namespace roifem::io
