// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What `roifem paper` reports: the paper's findings checked on the run, its Table 2, the
/// reductions' table and, driven by spatulas, the force the surgeon feels (printed); errors.csv,
/// reductions.csv, timing.csv and, with spatulas, force_errors.csv (written).
#include <filesystem>
#include <iosfwd>
#include <vector>

#include "experiments/paper_results.hpp"

namespace roifem::experiments {

void print_paper_report(const PaperResults& results, std::ostream& log);

/// The paper's four findings, checked on the paper's reduction's curves (setup-major, `n_ramps`
/// ramps each, fastest first) and step costs (the full model's first).
struct PaperFindings {
  bool steady_below_0_2_mm = true;       ///< steady-state mean error below 0.2 mm, every ramp and setup
  bool faster_ramp_peaks_higher = true;  ///< the faster the ramp, the higher the max-error peak
  bool smaller_roi_peaks_higher = true;  ///< setup 2 peaks above setup 1
  bool condensed_step_faster = true;     ///< the condensed models step faster than the full model
};
PaperFindings check_findings(const std::vector<PaperCurve>& curves, std::size_t n_ramps, const std::vector<double>& step_s);
/// Each curve's peaks and steady error, then the four findings with [yes] or [NO].
void print_findings(const std::vector<PaperCurve>& curves, std::size_t n_ramps, const std::vector<double>& step_s,
                    std::ostream& log);
/// The tables' CSV files into `out` (their columns: paper_results.hpp's lists).
void write_paper_tables(const PaperResults& results, const std::filesystem::path& out);

}  // namespace roifem::experiments
