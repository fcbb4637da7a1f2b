// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What `roifem paper` finds (paper_experiment.hpp): the error curves, Table 2's step costs, the
/// reductions' table, and the one column list of each result table, which errors.csv,
/// force_errors.csv, reductions.csv, timing.csv and the Python module's structured arrays all read
/// (io/result_table.hpp).
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "experiments/error_budget.hpp"
#include "io/result_table.hpp"

namespace roifem::experiments {

/// What widens the opening: the paper's two forces, or two spatulas that move its walls.
enum class PaperDrive { forces, spatulas };

struct PaperCurve {  ///< one setup, one reduction, one ramp
  std::string setup;
  bool static_condensation = true;   ///< the paper's reduction
  std::string reduction = "static";  ///< its label
  double ramp_s = 0;
  std::vector<double> mean_mm, max_mm;  ///< per step 1..steps
  /// Spatulas only, per step: the largest of the spatulas' force errors |F_reduced - F_full| and
  /// the largest force |F_full| (mN).
  std::vector<double> force_err_mN, force_full_mN;
};

struct PaperTiming {
  std::string model;
  Index nodes = 0, dofs = 0;
  double step_s_median = 0, step_s_p99 = 0;
  std::optional<double> setup_s;  ///< a condensed model's condensation (the full model has none)
};

struct ReductionRow {               ///< one setup, one reduction, at the fastest (first) ramp
  std::string setup, reduction;     ///< reduction: its label
  bool static_condensation = true;  ///< the paper's reduction
  Index dofs = 0, extra_dofs = 0;   ///< of the reduced system; beyond the ROI's own
  double ramp_s = 0, peak_max_mm = 0, steady_mean_mm = 0;
  double step_s_median = 0, setup_s = 0;
  std::optional<double> peak_force_err_mN;  ///< spatulas only
};

struct PaperResults {
  PaperDrive drive = PaperDrive::forces;
  double dt = 0;                             ///< s, the run's step
  std::vector<double> ramps_s;               ///< the run's ramps, in the curves' order within a setup
  double force_N = 0;                        ///< per wall: applied, or (spatulas) held at rest
  double opening_mm = 0;                     ///< static widening it gives
  std::vector<PaperCurve> curves;            ///< static condensation (the paper's), setup-major
  std::vector<PaperCurve> reduction_curves;  ///< every reduction (static included), every setup and ramp
  std::vector<ReductionRow> reductions;
  std::vector<PaperTiming> timing;     ///< full first, then the setups
  std::vector<Index> interface_nodes;  ///< per setup
  std::optional<ErrorBudget> budget;   ///< forces drive, when asked
};

/// Hansen & Larsen's Table 2 (1998 hardware): seconds per step.
inline constexpr double paper_full_step_s = 0.440, paper_setup1_step_s = 0.071, paper_setup2_step_s = 0.037;
/// The paper's Fig. 6: setup 1's max error at the 0.5 s ramp peaks at about 6 mm (mm).
inline constexpr double paper_peak_max_error_mm = 6.0;

/// The mean error averaged over the steps after the 100th (the damped transient's end).
double steady_mean(const PaperCurve& curve);
/// The same for the spatulas' force error (mN).
double steady_force_err(const PaperCurve& curve);

/// One step of one curve: a row of errors.csv and force_errors.csv.
struct PaperStep {
  const PaperCurve* curve = nullptr;
  long step = 0;  ///< 1..steps
  double time_s = 0;
};
/// Every curve's steps (results.reduction_curves, in order).
std::vector<PaperStep> paper_steps(const PaperResults& results);

/// errors.csv: the displacement errors per setup, reduction, ramp and step.
std::span<const io::Column<PaperStep>> error_columns();
/// force_errors.csv, driven by spatulas: the force errors per setup, reduction, ramp and step.
std::span<const io::Column<PaperStep>> force_error_columns();
/// reductions.csv: a row per setup and reduction at the fastest ramp.
std::span<const io::Column<ReductionRow>> reduction_columns();
/// timing.csv: Table 2, a row per model.
std::span<const io::Column<PaperTiming>> timing_columns();

}  // namespace roifem::experiments
