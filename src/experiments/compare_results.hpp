// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What `roifem compare` finds (compare_experiment.hpp): a row per run, the stability limits, and
/// the one column list of each table, which compare.csv, stability.csv, tools.csv and the Python
/// module's structured arrays all read (io/result_table.hpp).
#include <span>
#include <string>
#include <vector>

#include "integrators/stats.hpp"
#include "io/result_table.hpp"

namespace roifem::experiments {

/// With tools: the tools' force against the exact one, and the DAE forms' constraint drifts.
struct ToolFigures {
  double force_error_rel = 0;
  double position_drift_mm = 0, velocity_drift_mm_s = 0;
};

struct CompareRow {
  std::string integrator, mode;
  double dt_or_tol = 0;
  int theoretical_order = 0;  ///< the method's (its table row)
  integrators::Stats stats;   ///< the run's counters (integrators/stats.hpp)
  double wall_s = 0, err_max_mm = 0, err_rms_mm = 0, energy_drift = 0;
  ToolFigures tools;  ///< with tools (tools.csv)
  bool stable = true;
  /// "ok", "diverged: <the solver's message>" or "stopped at t = ... s after ... s (over --max-run-seconds ...)":
  /// a run that did not finish keeps its row, with this reason, and no error figures.
  std::string status = "ok";
  bool finished() const { return status == "ok"; }
  /// The run has error figures: it finished, and stably.
  bool has_figures() const { return finished() && stable; }
};

struct StabilityRow {
  std::string integrator;
  double omega_max = 0;  ///< rad/s, of the integrated system
  double predicted_dt = 0, measured_dt = 0;
};

struct CompareResults {
  std::vector<CompareRow> rows;
  std::vector<StabilityRow> stability;
  double omega_max = 0;  ///< rad/s, of the integrated system (a nonlinear one: its tangent's, the largest along the reference)
  bool nonlinear = false;
  /// Without a modal solution: the largest difference between the reference and its check (mm).
  double reference_agreement_mm = 0;
};

/// compare.csv: a row per run; on a nonlinear system with the Newton iterations too (a linear
/// one's file keeps its columns).
std::span<const io::Column<CompareRow>> compare_columns(bool nonlinear = false);
/// stability.csv: a row per explicit method.
std::span<const io::Column<StabilityRow>> stability_columns();
/// tools.csv, with tools: a row per run that has figures.
std::span<const io::Column<CompareRow>> tool_columns();

}  // namespace roifem::experiments
