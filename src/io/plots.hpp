// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// PNG plots are drawn by Python scripts (matplotlib, run by Debian's /usr/bin/python3) from the
/// CSV files a command wrote. A missing interpreter or library is a warning, not an error: the
/// numbers are in the CSV and HDF5 files already.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace roifem::io {

/// Runs scripts/plots/<script> with `directory` as its argument; returns true on success and
/// otherwise writes a warning to `log`. Looks in $ROIFEM_PLOT_DIR, the source tree, then the
/// installed share/roifem/plots.
bool run_plot_script(const std::string& script, const std::filesystem::path& directory, std::ostream& log,
                     const std::vector<std::string>& arguments = {});

}  // namespace roifem::io
