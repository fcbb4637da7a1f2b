// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What `roifem paper` reports: the paper's findings checked on the run, its Table 2, the
/// reductions' table and, driven by spatulas, the force the surgeon feels (printed); errors.csv,
/// reductions.csv, timing.csv and, with spatulas, force_errors.csv (written).
#include <iosfwd>

#include "experiments/paper_experiment.hpp"

namespace roifem::experiments {

/// The mean error averaged over the steps after the 100th (the damped transient's end).
double steady_mean(const PaperCurve& curve);
/// The same for the spatulas' force error (mN).
double steady_force_err(const PaperCurve& curve);

void print_paper_report(const PaperOptions& options, const PaperResults& results, std::ostream& log);
void write_paper_tables(const PaperOptions& options, const PaperResults& results);

}  // namespace roifem::experiments
