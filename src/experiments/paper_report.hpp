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

/// A finding checked on a run: it holds, it fails, or a run it needs stopped short (or took no
/// step), so that it was not measured: never "holds" from steps that were not taken.
enum class Finding { holds, fails, not_measured };

/// The paper's four findings, checked on the paper's reduction's curves (setup-major, `n_ramps`
/// ramps each, fastest first, each of `steps` steps when complete) and step costs (the full
/// model's first; 0 for a model that took no step).
struct PaperFindings {
  Finding steady_below_0_2_mm = Finding::holds;       ///< steady-state mean error below 0.2 mm, every ramp and setup
  Finding faster_ramp_peaks_higher = Finding::holds;  ///< the faster the ramp, the higher the max-error peak
  Finding smaller_roi_peaks_higher = Finding::holds;  ///< setup 2 peaks above setup 1
  Finding condensed_step_faster = Finding::holds;     ///< the condensed models step faster than the full model
  bool all_measured() const;
};
PaperFindings check_findings(const std::vector<PaperCurve>& curves, std::size_t n_ramps, long steps,
                             const std::vector<double>& step_s);
/// Each curve's peaks and steady error ("-" where the run stopped before step 101), then the four
/// findings with [yes], [NO] or [--] (not measured: a run it needs stopped short).
void print_findings(const std::vector<PaperCurve>& curves, std::size_t n_ramps, long steps, const std::vector<double>& step_s,
                    std::ostream& log);
/// The tables' CSV files into `out` (their columns: paper_results.hpp's lists).
void write_paper_tables(const PaperResults& results, const std::filesystem::path& out);

}  // namespace roifem::experiments
