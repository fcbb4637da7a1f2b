// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What `roifem paper` reports: the paper's findings checked on the run, its Table 2, the
/// reductions' table and, driven by spatulas, the force the surgeon feels (printed); errors.csv,
/// reductions.csv, timing.csv and, with spatulas, force_errors.csv (written).
#include <filesystem>
#include <iosfwd>

#include "experiments/paper_results.hpp"

namespace roifem::experiments {

void print_paper_report(const PaperResults& results, std::ostream& log);
/// The tables' CSV files into `out` (their columns: paper_results.hpp's lists).
void write_paper_tables(const PaperResults& results, const std::filesystem::path& out);

}  // namespace roifem::experiments
