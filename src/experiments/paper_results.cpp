// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/paper_results.hpp"

#include <array>

namespace roifem::experiments {

namespace {

double mean_after_step_100(const std::vector<double>& values) {
  double sum = 0;
  long count = 0;
  for (std::size_t k = 100; k < values.size(); ++k, ++count) sum += values[k];
  return count ? sum / static_cast<double>(count) : 0.0;
}

using io::Cell;
using io::Column;

/// A per-step series of the step's curve.
double at(const std::vector<double>& series, const PaperStep& s) { return series[static_cast<std::size_t>(s.step - 1)]; }
Cell optional_cell(const std::optional<double>& x) { return x ? Cell(*x) : Cell(); }

const Column<PaperStep> setup_column{"setup", "setup1, setup2, ... (by ROI size, largest first)",
                                     [](const PaperStep& s) -> Cell { return s.curve->setup; }};
const Column<PaperStep> reduction_column{"reduction", "the static part's reduction (static: the paper's condensation)",
                                         [](const PaperStep& s) -> Cell { return s.curve->reduction; }};
const Column<PaperStep> ramp_column{"ramp_s", "the load's ramp time (s)",
                                    [](const PaperStep& s) -> Cell { return s.curve->ramp_s; }, "%g"};
const Column<PaperStep> step_column{"step", "the step, 1..steps", [](const PaperStep& s) -> Cell { return s.step; }};
const Column<PaperStep> time_column{"time_s", "the step's time (s)", [](const PaperStep& s) -> Cell { return s.time_s; }, "%.4f"};

const std::array<Column<PaperStep>, 7> errors{{
    setup_column,
    reduction_column,
    ramp_column,
    step_column,
    time_column,
    {"mean_mm", "the mean over the ROI's nodes of |u_reduced - u_full| (mm)",
     [](const PaperStep& s) -> Cell { return at(s.curve->mean_mm, s); }, "%.9g"},
    {"max_mm", "the largest over the ROI's nodes of |u_reduced - u_full| (mm)",
     [](const PaperStep& s) -> Cell { return at(s.curve->max_mm, s); }, "%.9g"},
}};

const std::array<Column<PaperStep>, 7> force_errors{{
    setup_column,
    reduction_column,
    ramp_column,
    step_column,
    time_column,
    {"force_full_mN", "the larger of the two spatulas' force on the tissue in the full model (mN)",
     [](const PaperStep& s) -> Cell { return at(s.curve->force_full_mN, s); }, "%.9g"},
    {"force_err_mN", "the larger of the two spatulas' |F_reduced - F_full| (mN)",
     [](const PaperStep& s) -> Cell { return at(s.curve->force_err_mN, s); }, "%.9g"},
}};

const std::array<Column<ReductionRow>, 10> reductions{{
    {"setup", "setup1, setup2, ...", [](const ReductionRow& r) -> Cell { return r.setup; }},
    {"reduction", "the static part's reduction", [](const ReductionRow& r) -> Cell { return r.reduction; }},
    {"dofs", "the reduced system's degrees of freedom", [](const ReductionRow& r) -> Cell { return static_cast<long>(r.dofs); }},
    {"extra_dofs", "those beyond the ROI's own (modes kept)",
     [](const ReductionRow& r) -> Cell { return static_cast<long>(r.extra_dofs); }},
    {"ramp_s", "the fastest ramp (s)", [](const ReductionRow& r) -> Cell { return r.ramp_s; }, "%g"},
    {"peak_max_mm", "the peak over the steps of the max error (mm)", [](const ReductionRow& r) -> Cell { return r.peak_max_mm; },
     "%.9g"},
    {"steady_mean_mm", "the mean error averaged over the steps after the 100th (mm)",
     [](const ReductionRow& r) -> Cell { return r.steady_mean_mm; }, "%.9g"},
    {"step_s_median", "the trapezoidal rule's median step cost (s)",
     [](const ReductionRow& r) -> Cell { return r.step_s_median; }, "%.6e"},
    {"setup_s", "the reduction's setup time (s)", [](const ReductionRow& r) -> Cell { return r.setup_s; }, "%.6e"},
    {"peak_force_err_mN", "driven by spatulas: the peak of the spatulas' force error (mN)",
     [](const ReductionRow& r) { return optional_cell(r.peak_force_err_mN); }, "%.9g"},
}};

const std::array<Column<PaperTiming>, 7> timing{{
    {"model", "full, setup1, setup2, ...", [](const PaperTiming& t) -> Cell { return t.model; }},
    {"nodes", "the model's nodes (a setup: its ROI's)", [](const PaperTiming& t) -> Cell { return static_cast<long>(t.nodes); }},
    {"dofs", "the integrated system's degrees of freedom",
     [](const PaperTiming& t) -> Cell { return static_cast<long>(t.dofs); }},
    {"step_s_median", "the median step cost of the trapezoidal rule (s)",
     [](const PaperTiming& t) -> Cell { return t.step_s_median; }, "%.6e"},
    {"frame_rate_hz", "1 / step_s_median (Hz)", [](const PaperTiming& t) -> Cell { return 1.0 / t.step_s_median; }, "%.1f"},
    {"step_s_p99", "the 99th percentile of the step cost (s)", [](const PaperTiming& t) -> Cell { return t.step_s_p99; }, "%.6e"},
    {"setup_s", "a setup's condensation time (s); empty for the full model",
     [](const PaperTiming& t) { return optional_cell(t.setup_s); }, "%.6e"},
}};

}  // namespace

double steady_mean(const PaperCurve& c) { return mean_after_step_100(c.mean_mm); }
double steady_force_err(const PaperCurve& c) { return mean_after_step_100(c.force_err_mN); }

std::vector<PaperStep> paper_steps(const PaperResults& results) {
  std::vector<PaperStep> steps;
  for (const auto& c : results.reduction_curves)
    for (std::size_t k = 0; k < c.mean_mm.size(); ++k)
      steps.push_back({&c, static_cast<long>(k + 1), static_cast<double>(k + 1) * results.dt});
  return steps;
}

std::span<const Column<PaperStep>> error_columns() { return errors; }
std::span<const Column<PaperStep>> force_error_columns() { return force_errors; }
std::span<const Column<ReductionRow>> reduction_columns() { return reductions; }
std::span<const Column<PaperTiming>> timing_columns() { return timing; }

}  // namespace roifem::experiments
